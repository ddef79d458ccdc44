// Publishes one plausible message of every atlasd type on atlasd's default channels, at 10 Hz,
// for the given number of seconds (default 15). Used by scripts/atlas-spy-check to show that
// atlas-spy decodes every channel. Run as a single-file program:
//   java -cp /usr/share/java/lcm.jar:atlasd-lcmtypes.jar AtlasSpyDemoPublisher.java [SECONDS]
// It publishes on LCM_DEFAULT_URL: only ever run it inside a private network namespace or with
// a memq:// URL, never onto a real network.

import atlasd.*;
import lcm.lcm.LCM;

public class AtlasSpyDemoPublisher {
  public static void main(String[] args) throws Exception {
    double seconds = args.length > 0 ? Double.parseDouble(args[0]) : 15.0;
    LCM lcm = LCM.getSingleton();
    long start = System.nanoTime();
    for (int step = 0; (System.nanoTime() - start) / 1e9 < seconds; ++step) {
      long uptime = (System.nanoTime() - start) / 1000;
      long utime = System.currentTimeMillis() * 1000;  // microseconds since the epoch, as atlasd
      double t = step * 0.1;

      pose_t pose = new pose_t();
      pose.utime = utime;
      pose.frame_id = 3;
      pose.x = Math.cos(t);
      pose.y = Math.sin(t);
      pose.theta = t % Math.PI;
      pose.covariance = new double[] {0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.002};
      pose.q = 0.87;
      lcm.publish("ATLAS_POSE", pose);

      reference_pose_t reference = new reference_pose_t();
      reference.utime = utime;
      reference.reference_frame_id = 0;
      reference.placed = true;
      reference.frame_id = pose.frame_id;
      reference.frame_x = 4.0;
      reference.frame_y = -2.0;
      reference.frame_theta = 0.5;
      reference.frame_covariance = new double[] {0.04, 0, 0, 0, 0.04, 0, 0, 0, 0.004};
      reference.x = 4.0 + Math.cos(0.5) * pose.x - Math.sin(0.5) * pose.y;
      reference.y = -2.0 + Math.sin(0.5) * pose.x + Math.cos(0.5) * pose.y;
      reference.theta = Math.IEEEremainder(0.5 + pose.theta, 2 * Math.PI);
      reference.covariance = new double[] {0.05, 0, 0, 0, 0.05, 0, 0, 0, 0.006};
      reference.hops = 2;
      reference.q = pose.q;
      lcm.publish("ATLAS_REFERENCE_POSE", reference);

      local_map_t map = new local_map_t();
      map.utime = utime;
      map.frame_id = 3;
      map.capacity = 30;
      map.robot_x = pose.x;
      map.robot_y = pose.y;
      map.robot_theta = pose.theta;
      map.num_lines = 4;
      map.lines = new line_segment_t[map.num_lines];
      for (int i = 0; i < map.num_lines; ++i) {
        line_segment_t l = new line_segment_t();
        l.id = i;
        l.rho = 2.0 + i;
        l.alpha = -Math.PI + i * Math.PI / 2;
        l.covariance = new double[] {0.0004, 0, 0, 0.0001};
        l.x0 = -1;
        l.y0 = i;
        l.x1 = 3;
        l.y1 = i;
        map.lines[i] = l;
      }
      lcm.publish("ATLAS_LOCAL_MAP", map);

      if (step % 10 == 0) {
        atlas_graph_t g = new atlas_graph_t();
        g.utime = utime;
        g.step = step;
        g.dominant_frame_id = 3;
        g.num_frames = 4;
        g.frames = new atlas_frame_t[g.num_frames];
        for (int i = 0; i < g.num_frames; ++i) {
          atlas_frame_t f = new atlas_frame_t();
          f.id = i;
          f.num_features = 10 + i;
          f.created_step = i * 100;
          f.degree = i == 0 || i == 3 ? 1 : 2;
          f.projected = true;
          f.x = i * 8.0;
          g.frames[i] = f;
        }
        g.num_edges = 3;
        g.edges = new atlas_edge_t[g.num_edges];
        for (int i = 0; i < g.num_edges; ++i) {
          atlas_edge_t e = new atlas_edge_t();
          e.frame_from = i;
          e.frame_to = i + 1;
          e.x = 8.0;
          e.covariance = new double[] {0.05, 0, 0, 0, 0.05, 0, 0, 0, 0.004};
          e.kind = i == 1 ? atlas_edge_t.KIND_REFINED : atlas_edge_t.KIND_GENESIS;
          e.origin = atlas_edge_t.KIND_GENESIS;
          e.refinements = i == 1 ? 2 : 0;
          g.edges[i] = e;
        }
        lcm.publish("ATLAS_GRAPH", g);

        hypotheses_t hs = new hypotheses_t();
        hs.utime = utime;
        hs.dominant_id = 12;
        hs.num_hypotheses = 2;
        hs.hypotheses = new hypothesis_t[2];
        for (int i = 0; i < 2; ++i) {
          hypothesis_t h = new hypothesis_t();
          h.id = 11 + i;
          h.frame_id = 2 + i;
          h.state = i == 1 ? hypothesis_t.STATE_DOMINANT : hypothesis_t.STATE_JUVENILE;
          h.q = i == 1 ? 0.87 : 0.41;
          h.steps = 40 * (i + 1);
          h.covariance = new double[9];
          hs.hypotheses[i] = h;
        }
        lcm.publish("ATLAS_HYPOTHESES", hs);

        health_t health = new health_t();
        health.utime = utime;
        health.uptime_us = uptime;
        health.steps = step;
        health.period_steps = 10;
        health.step_time_min_us = 210;
        health.step_time_median_us = 380;
        health.step_time_p99_us = 900;
        health.step_time_max_us = 950;
        health.step_budget_us = 10000;
        health.num_drivers = 2;
        health.drivers = new driver_health_t[2];
        String[] names = {"laser", "odometry"};
        String[] devices = {"/dev/ttyUSB0", "can0"};
        for (int i = 0; i < 2; ++i) {
          driver_health_t d = new driver_health_t();
          d.name = names[i];
          d.device = devices[i];
          d.state = driver_health_t.STATE_RUNNING;
          d.queue_capacity = 8;
          d.messages = step * (i + 1);
          d.message_rate_hz = i == 0 ? 75 : 50;
          d.last_error = "";
          d.device_status = i == 0 ? "ok" : "";
          health.drivers[i] = d;
        }
        health.num_frames = 4;
        health.num_edges = 3;
        health.num_juvenile = 1;
        health.num_mature = 1;
        health.dominant_frame_id = 3;
        health.resident_memory_bytes = 24L << 20;
        health.status = "frame 3, q 0.87, 4 frames, step p99 0.9 ms";
        health.version = "demo";
        lcm.publish("ATLAS_HEALTH", health);
      }

      odometry_t odo = new odometry_t();
      odo.utime = utime;
      odo.x = pose.x;
      odo.y = pose.y;
      odo.theta = pose.theta;
      lcm.publish("ATLAS_RAW_ODOMETRY", odo);

      laser_scan_t scan = new laser_scan_t();
      scan.utime = utime;
      scan.angle_min = (float) (-Math.PI / 2);
      scan.angle_increment = (float) (Math.PI / 180);
      scan.max_range = 8.0f;
      scan.num_ranges = 181;
      scan.ranges = new float[181];
      for (int i = 0; i < 181; ++i) scan.ranges[i] = 2.0f + (i % 7) * 0.1f;
      scan.sensor_x = 0.1;
      lcm.publish("ATLAS_RAW_LASER", scan);

      sonar_t sonar = new sonar_t();
      sonar.utime = utime;
      sonar.num_returns = 2;
      sonar.transducer = new short[] {(short) (step % 16), (short) ((step + 8) % 16)};
      sonar.range = new float[] {1.5f, Float.POSITIVE_INFINITY};
      lcm.publish("ATLAS_RAW_SONAR", sonar);

      Thread.sleep(100);
    }
    System.exit(0);
  }
}
