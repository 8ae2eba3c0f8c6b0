#include "export/robot/robot_program.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  std::string s = buf;
  if (s == "-0.0000" || s == "-0.000000" || s == "-0.000000000") s.erase(0, 1);
  return s;
}
std::string mm(double v) { return fmt("%.4f", v); }

std::string part_name(const std::string& base, int part) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "_p%02d", part);
  return base + buf;
}

std::string krl_frame(const Eigen::Isometry3d& t) {
  const Vec3 p = t.translation();
  const std::array<double, 3> abc = rotation_abc(t.linear());
  return "{X " + mm(p.x()) + ",Y " + mm(p.y()) + ",Z " + mm(p.z()) + ",A " + mm(abc[0]) + ",B " +
         mm(abc[1]) + ",C " + mm(abc[2]) + "}";
}

std::string quaternion(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const char* f = "%.9f";
  return "[" + fmt(f, q.w()) + "," + fmt(f, q.x()) + "," + fmt(f, q.y()) + "," + fmt(f, q.z()) +
         "]";
}

std::string rapid_pose(const Eigen::Isometry3d& t) {
  const Vec3 p = t.translation();
  return "[[" + mm(p.x()) + "," + mm(p.y()) + "," + mm(p.z()) + "]," + quaternion(t.linear()) + "]";
}

int quadrant(double deg) { return static_cast<int>(std::floor(deg / 90.0)); }

std::vector<std::pair<int, int>> parts_of(const RobotMotion& m, int max_points) {
  std::vector<std::pair<int, int>> parts;  // [first, end)
  const int n = static_cast<int>(m.targets.size());
  for (int i = 0; i < n; i += max_points) parts.push_back({i, std::min(n, i + max_points)});
  return parts;
}

std::string header_comment(const RobotMotion& m, const std::string& job, const RobotOptions& ro,
                           const char* c) {
  std::string s;
  s += std::string(c) + " windplan: job " + job + ", " + ro.arm_name + " with " +
       ro.positioner_name + " (E1)\n";
  s += std::string(c) + " " + std::to_string(m.targets.size()) + " targets, cycle " +
       fmt("%.1f", m.cycle_time) +
       " s; BASE = the positioner frame (x = the E1 axis), TOOL = the "
       "payout eye (x towards the mandrel axis)\n";
  return s;
}

std::vector<ProgramFile> krl(const RobotMotion& m, const std::string& job, const RobotOptions& ro) {
  const std::string base = robot_program_base(job);
  const auto parts = parts_of(m, ro.max_points);
  std::vector<ProgramFile> files;
  std::string src = "&ACCESS RVP\n&REL 1\nDEF " + base + "( )\n";
  src += header_comment(m, job, ro, ";");
  src += "$TOOL = TOOL_EYE\n$BASE = BASE_MANDREL\n$VEL_EXTAX[1] = 100\n$APO.CDIS = 0.5\n";
  for (std::size_t p = 0; p < parts.size(); ++p) src += part_name(base, int(p) + 1) + "( )\n";
  src += "END\n";
  std::string dat = "&ACCESS RVP\n&REL 1\nDEFDAT " + base + " PUBLIC\n";
  dat += "DECL FRAME TOOL_EYE=" + krl_frame(m.tool) + "\n";
  dat += "DECL FRAME BASE_MANDREL=" + krl_frame(m.base) + "\n";
  dat += "ENDDAT\n";
  files.push_back({base + ".src", src});
  files.push_back({base + ".dat", dat});
  // $VEL_EXTAX[1] holds from one part to the next (a system variable; the main program sets it
  // to 100 before the first part): a part whose first move wants the value the previous part
  // left writes nothing, any other writes it (before: every part assumed 100, and a part after
  // one that ended at 0.000001% ran its first move at that, 1.8e6 s for 3.3 deg of E1).
  std::string last_extax = "100.000000";
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::string name = part_name(base, int(p) + 1);
    std::string s = "&ACCESS RVP\n&REL 1\nDEF " + name + "( )\n";
    s += "; targets " + std::to_string(parts[p].first + 1) + " to " +
         std::to_string(parts[p].second) + " of " + std::to_string(m.targets.size()) + "\n";
    std::string d = "&ACCESS RVP\n&REL 1\nDEFDAT " + name + " PUBLIC\n";
    std::string last_vel;
    for (int i = parts[p].first; i < parts[p].second; ++i) {
      const RobotTarget& t = m.targets[i];
      const std::string var = "XP" + std::to_string(i + 1);
      std::string pose = krl_frame(t.eye);
      pose.pop_back();
      d += "DECL E6POS " + var + "=" + pose + ",S " + std::to_string(t.status) + ",T " +
           std::to_string(t.turn) + ",E1 " + mm(t.e1) + ",E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}\n";
      if (t.tie_on || i == 0) {
        s += "PTP " + var + "\n";
        continue;
      }
      const double dist =
          (t.eye.translation() - m.targets[i - 1].eye.translation()).norm() / 1000.0;  // m
      const double vel = t.duration > 0.0 ? std::max(dist / t.duration, 1e-9) : 2.0;
      const std::string v = fmt("%.9f", vel);
      if (v != last_vel) s += "$VEL.CP = " + v + "\n";
      last_vel = v;
      // E1 at the speed the move's time asks for (% of its max): a move of the positioner with
      // the eye (nearly) still takes its time from $VEL_EXTAX, not from $VEL.CP.
      // (from E1 as written, to 1e-4 deg: a slow E1 move's percentage from the unrounded values
      // would time the rounded one far longer)
      const double de1 = std::fabs(std::stod(mm(t.e1)) - std::stod(mm(m.targets[i - 1].e1)));
      const double pct =
          t.duration > 0.0 ? std::clamp(100.0 * de1 / t.duration / ro.e1_max_velocity, 1e-6, 100.0)
                           : 100.0;
      const std::string e = fmt("%.6f", pct);
      if (e != last_extax) s += "$VEL_EXTAX[1] = " + e + "\n";
      last_extax = e;
      s += "LIN " + var + " C_DIS\n";
    }
    s += "END\n";
    d += "ENDDAT\n";
    files.push_back({name + ".src", s});
    files.push_back({name + ".dat", d});
  }
  return files;
}

std::vector<ProgramFile> rapid(const RobotMotion& m, const std::string& job,
                               const RobotOptions& ro) {
  const std::string base = robot_program_base(job);
  const auto parts = parts_of(m, ro.max_points);
  std::vector<ProgramFile> files;
  std::string mod = "MODULE " + base + "\n";
  mod += header_comment(m, job, ro, "  !");
  mod +=
      "  PERS tooldata tEye := [TRUE," + rapid_pose(m.tool) + ",[1,[0,0,50],[1,0,0,0],0,0,0]];\n";
  mod += "  PERS wobjdata wPositioner := [FALSE,TRUE,\"\"," + rapid_pose(m.base) +
         ",[[0,0,0],[1,0,0,0]]];\n";
  mod += "  PROC main()\n";
  for (std::size_t p = 0; p < parts.size(); ++p)
    mod += "    " + part_name(base, int(p) + 1) + ";\n";
  mod += "  ENDPROC\nENDMODULE\n";
  files.push_back({base + ".mod", mod});
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::string name = part_name(base, int(p) + 1);
    std::string s = "MODULE " + name + "\n  ! targets " + std::to_string(parts[p].first + 1) +
                    " to " + std::to_string(parts[p].second) + " of " +
                    std::to_string(m.targets.size()) + "\n  PROC " + name + "()\n";
    for (int i = parts[p].first; i < parts[p].second; ++i) {
      const RobotTarget& t = m.targets[i];
      std::string rt = rapid_pose(t.eye);
      rt.pop_back();
      rt += ",[" + std::to_string(quadrant(t.q[0])) + "," + std::to_string(quadrant(t.q[3])) + "," +
            std::to_string(quadrant(t.q[5])) + "," + std::to_string(t.status) + "],[" + mm(t.e1) +
            ",9E9,9E9,9E9,9E9,9E9]]";
      if (t.tie_on || i == 0) {
        s += "    MoveJ " + rt + ",v1000,fine,tEye\\WObj:=wPositioner;\n";
      } else {
        s += "    MoveL " + rt + ",v1000\\T:=" + fmt("%.6f", t.duration) +
             ",z1,tEye\\WObj:=wPositioner;\n";
      }
    }
    s += "  ENDPROC\nENDMODULE\n";
    files.push_back({name + ".mod", s});
  }
  return files;
}

}  // namespace

std::string robot_program_base(const std::string& job_name) {
  std::string s = "wp_";
  for (char c : job_name) {
    const unsigned char u = static_cast<unsigned char>(c);
    s += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : '_';
    if (s.size() >= 20) break;
  }
  return s;
}

std::string robot_program_main(const std::string& job_name, const std::string& dialect) {
  return robot_program_base(job_name) + (dialect == "rapid" ? ".mod" : ".src");
}

std::vector<ProgramFile> robot_program(const RobotMotion& motion, const std::string& job_name,
                                       const MachineOptions& machine) {
  const RobotOptions& ro = machine.robot;
  if (ro.dialect == "krl") return krl(motion, job_name, ro);
  if (ro.dialect == "rapid") return rapid(motion, job_name, ro);
  throw ConfigError("machine.robot.dialect: unknown robot dialect '" + ro.dialect +
                    "' (krl or rapid)");
}

}  // namespace windplan
