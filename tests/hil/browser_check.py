#!/usr/bin/env python3
"""Opens a page in headless Chromium and reads its DOM over the DevTools protocol (a small
WebSocket client on the standard library: nothing to install at test time).

Usage: browser_check.py CHROMIUM URL PROFILE_DIR SCREENSHOT.png SECONDS

Loads URL, then watches atlas-view's page for up to SECONDS: it must show frames, a placed
pose and the health panel, and then update (the update counter, the pose and the health line
change). Prints what it read, saves a screenshot (after the page's "fit"), exits 0 when all of
it was seen, else 1. With VIEW_MIN_SECONDS=S in the environment it watches at least S seconds
before the screenshot (a larger map for docs/atlas-view.png).
"""
import base64
import json
import os
import socket
import struct
import subprocess
import sys
import time
import urllib.request


class DevTools:
    """One WebSocket to a page target: JSON commands, answers matched by id."""

    def __init__(self, ws_url):
        rest = ws_url.split("://", 1)[1]
        hostport, path = rest.split("/", 1)
        host, port = hostport.rsplit(":", 1)
        self.sock = socket.create_connection((host, int(port)), timeout=30)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall((f"GET /{path} HTTP/1.1\r\nHost: {hostport}\r\nUpgrade: websocket\r\n"
                           f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                           "Sec-WebSocket-Version: 13\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            if not chunk:
                raise RuntimeError("DevTools closed the WebSocket handshake")
            head += chunk
        if b" 101 " not in head.split(b"\r\n", 1)[0]:
            raise RuntimeError("DevTools refused the WebSocket: %r" % head[:200])
        self.next_id = 0

    def _recv_exact(self, n):
        buf = b""
        while len(buf) < n:
            chunk = self.sock.recv(n - len(buf))
            if not chunk:
                raise RuntimeError("DevTools closed the WebSocket")
            buf += chunk
        return buf

    def _send(self, text):
        data = text.encode()
        head = bytes([0x81])
        if len(data) < 126:
            head += bytes([0x80 | len(data)])
        elif len(data) < 65536:
            head += bytes([0x80 | 126]) + struct.pack(">H", len(data))
        else:
            head += bytes([0x80 | 127]) + struct.pack(">Q", len(data))
        mask = os.urandom(4)
        self.sock.sendall(head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))

    def _recv_message(self):
        parts = []
        while True:
            b0, b1 = self._recv_exact(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._recv_exact(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._recv_exact(8))[0]
            payload = self._recv_exact(n)
            opcode = b0 & 0x0F
            if opcode == 8:
                raise RuntimeError("DevTools closed the WebSocket")
            if opcode in (0, 1, 2):
                parts.append(payload)
                if b0 & 0x80:
                    return json.loads(b"".join(parts))

    def call(self, method, **params):
        self.next_id += 1
        self._send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            msg = self._recv_message()
            if msg.get("id") == self.next_id:
                if "error" in msg:
                    raise RuntimeError("%s: %s" % (method, msg["error"]))
                return msg["result"]

    def evaluate(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True)
        return r["result"].get("value")


READ_PAGE = """JSON.stringify({
  updates: Number(document.body.dataset.updates || 0),
  conn: document.getElementById('conn').dataset.state,
  framesDrawn: Number(document.getElementById('frames-drawn').textContent),
  framesTotal: Number(document.getElementById('frames-total').textContent),
  edges: Number(document.getElementById('edges').textContent),
  remembered: Number(document.getElementById('remembered').textContent),
  pose: document.getElementById('pose').textContent,
  health: document.getElementById('health-summary').textContent,
  drivers: Array.from(document.querySelectorAll('#drivers tr[data-driver]')).map(
      r => r.dataset.driver + '=' + r.dataset.state),
  hypotheses: document.querySelectorAll('#hypotheses tr').length,
})"""


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    chromium, url, profile, screenshot, seconds = sys.argv[1:]
    deadline = time.monotonic() + float(seconds)
    port_file = os.path.join(profile, "DevToolsActivePort")
    browser = subprocess.Popen(
        [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-extensions", "--disable-dev-shm-usage", "--remote-debugging-port=0",
         "--remote-allow-origins=*", "--user-data-dir=" + profile, "--window-size=1280,800",
         "about:blank"],
        stdout=subprocess.DEVNULL, stderr=open(os.path.join(profile, "..", "chromium.err"), "w"))
    try:
        while not os.path.exists(port_file):
            if browser.poll() is not None or time.monotonic() > deadline:
                print("FAIL: chromium did not start (exit %s)" % browser.poll())
                return 1
            time.sleep(0.1)
        time.sleep(0.2)
        port = open(port_file).read().split()[0]
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%s/json/list" % port))
        page = next(t for t in targets if t.get("type") == "page")
        dt = DevTools(page["webSocketDebuggerUrl"])
        dt.call("Page.enable")
        dt.call("Page.navigate", url=url)
        first = None
        last = None
        earliest = time.monotonic() + float(os.environ.get("VIEW_MIN_SECONDS", "0"))
        while time.monotonic() < deadline:
            time.sleep(0.5)
            last = json.loads(dt.evaluate(READ_PAGE) or "{}")
            shown = (last.get("updates", 0) > 0 and last["framesDrawn"] > 0 and
                     "x " in last["pose"] and len(last["drivers"]) >= 2 and
                     last["remembered"] > 0 and "steps" in last["health"])
            if first is None:
                if shown:
                    first = last
                    print("first:", json.dumps(first))
                continue
            if (last["updates"] >= first["updates"] + 3 and last["pose"] != first["pose"] and
                    last["health"] != first["health"] and time.monotonic() >= earliest):
                break
        print("last: ", json.dumps(last))
        dt.evaluate("fit()")
        time.sleep(0.3)
        shot = dt.call("Page.captureScreenshot", format="png")
        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        if first is None:
            print("FAIL: the page never showed frames with lines, a placed pose and the drivers")
            return 1
        if last is first or last["updates"] < first["updates"] + 3:
            print("FAIL: the page did not update")
            return 1
        if last["pose"] == first["pose"] or last["health"] == first["health"]:
            print("FAIL: the pose or the health panel did not change")
            return 1
        if any(not d.endswith("=running") for d in last["drivers"]):
            print("FAIL: a driver is not running: %s" % last["drivers"])
            return 1
        return 0
    finally:
        browser.terminate()
        try:
            browser.wait(5)
        except subprocess.TimeoutExpired:
            browser.kill()


if __name__ == "__main__":
    sys.exit(main())
