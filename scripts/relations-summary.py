#!/usr/bin/env python3
"""One line per run name from the outputs of scripts/eval-kinds.sh and scripts/eval-tuning.sh.

Usage: relations-summary.py OUT NAMES SEED...

NAMES is a space-separated list; OUT/NAME/seed-SEED/ holds all.json, all_odometry.json,
returns.json, returns_odometry.json (atlas-eval --json: the atlas along its Dijkstra paths and
dead reckoning on the same relations), returns.relations, returns_errors.tsv and atlas-replay's
summary.json. Per name: mean error over all relations (atlas, odometry; the seeds where the atlas
is no worse), mean error on the returns, false closures (chi2 3 dof > 14.16), returns joined
(same frame, neighbouring frames or a map-match edge) of all returns, and the step CPU time
(median of the seeds' medians, largest max, ms).
"""
import json
import os
import statistics
import sys


def load(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return None


def main():
    out, names, seeds = sys.argv[1], sys.argv[2].split(), sys.argv[3:]
    hdr = ("name", "seeds", "atlas m", "atlas deg", "odo m", "odo deg", "ok", "ret atlas m",
           "ret odo m", "false", "joined", "step ms", "max ms")
    print("%-13s %5s %8s %9s %7s %7s %5s %11s %9s %5s %11s %7s %7s" % hdr)
    for name in names:
        rows, ok, false, joined, returns, ret, med, mx = [], 0, 0, 0, 0, [], [], []
        for s in seeds:
            d = os.path.join(out, name, "seed-" + s)
            a, o = load(os.path.join(d, "all.json")), load(os.path.join(d, "all_odometry.json"))
            summary = load(os.path.join(d, "summary.json"))
            if not a or not o or not summary:
                continue
            rows.append((a["translation_m"]["mean"], a["rotation_deg"]["mean"],
                         o["translation_m"]["mean"], o["rotation_deg"]["mean"]))
            ok += a["translation_m"]["mean"] <= o["translation_m"]["mean"]
            false += summary.get("false_closures_chi2", 0)
            med.append(summary["step_cpu_ns_median"] * 1e-6)
            mx.append(summary["step_cpu_ns_max"] * 1e-6)
            ra = load(os.path.join(d, "returns.json"))
            ro = load(os.path.join(d, "returns_odometry.json"))
            if ra and ro:
                ret.append((ra["translation_m"]["mean"], ro["translation_m"]["mean"]))
                errors = [l.split() for l in open(os.path.join(d, "returns_errors.tsv"))
                          if not l.startswith("#")]
                returns += sum(1 for _ in open(os.path.join(d, "returns.relations")))
                joined += sum(1 for e in errors if len(e) > 4 and e[4] != "chain")
        if not rows:
            print("%-13s %5s" % (name, "none"))
            continue
        mean = lambda k, v: sum(r[k] for r in v) / len(v)
        print("%-13s %5d %8.3f %9.2f %7.3f %7.2f %5s %11s %9s %5d %11s %7.2f %7.2f" % (
            name, len(rows), mean(0, rows), mean(1, rows), mean(2, rows), mean(3, rows),
            "%d/%d" % (ok, len(rows)),
            "%.3f" % mean(0, ret) if ret else "-", "%.3f" % mean(1, ret) if ret else "-",
            false, "%d/%d" % (joined, returns), statistics.median(med), max(mx)))


if __name__ == "__main__":
    main()
