// viewer.html as text (export/plots/viewer.h): the page's structure, its data read back with an
// independent base64 decoder, decimation under a size limit, bad options. The page in a browser:
// tests/export/plots/viewer_browser_test.cpp.
#include "export/plots/viewer.h"

#include <cstdint>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/export/plan_fixtures.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// The value of "key":"..." in the page's data block.
std::string string_field(const std::string& html, const std::string& key) {
  const std::string k = "\"" + key + "\":\"";
  const std::size_t p = html.find(k);
  if (p == std::string::npos) return "";
  const std::size_t q = html.find('"', p + k.size());
  return html.substr(p + k.size(), q - p - k.size());
}

std::vector<unsigned char> unbase64(const std::string& s) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::vector<unsigned char> out;
  int bits = 0;
  unsigned acc = 0;  // only the last 14 bits matter (UBSan: an int shifted on overflowed)
  for (char c : s) {
    const int v = val(c);
    if (v < 0) break;  // '=' padding
    acc = ((acc << 6) | static_cast<unsigned>(v)) & 0x3fffu;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

std::vector<float> floats(const std::string& b64) {
  const std::vector<unsigned char> bytes = unbase64(b64);
  std::vector<float> f(bytes.size() / 4);
  std::memcpy(f.data(), bytes.data(), f.size() * 4);  // little-endian host, as the page
  return f;
}

TEST(Base64, Rfc4648Vectors) {
  auto b = [](const char* s) {
    return base64(reinterpret_cast<const unsigned char*>(s), std::strlen(s));
  };
  EXPECT_EQ(b(""), "");
  EXPECT_EQ(b("f"), "Zg==");
  EXPECT_EQ(b("fo"), "Zm8=");
  EXPECT_EQ(b("foo"), "Zm9v");
  EXPECT_EQ(b("foob"), "Zm9vYg==");
  EXPECT_EQ(b("fooba"), "Zm9vYmE=");
  EXPECT_EQ(b("foobar"), "Zm9vYmFy");
}

TEST(ViewerPage, SelfContainedWithThePlansData) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 200, 3);
  plan.job_name = "tube </script> <b>";
  plan.metrics.band_width = 6;
  plan.metrics.warnings = {"slippage above mu"};
  const Mesh mesh(test::open_cylinder(50, 700, 24, 10));
  const MachineOptions machine;  // (named: GCC 12 warns maybe-uninitialized on the temporary)
  const Motion motion = compute_motion(plan, machine);
  const ViewerPage page = viewer_page(plan, mesh, motion);
  const std::string& h = page.html;
  EXPECT_EQ(h.rfind("<!DOCTYPE html>", 0), 0u);
  // Three scripts (data, three.js, the viewer) and nothing loaded from elsewhere.
  EXPECT_EQ(count(h, "</script>"), 3);
  EXPECT_EQ(count(h, "<script src"), 0);
  EXPECT_EQ(count(h, "http://"), count(h, "http://www.w3.org"));  // namespaces only
  EXPECT_NE(h.find("REVISION=\"111\""), std::string::npos);
  EXPECT_NE(h.find("windplan-viewer: frame"), std::string::npos);
  EXPECT_NE(h.find("slippage above mu"), std::string::npos);
  EXPECT_NE(h.find("<title>windplan viewer: tube &lt;/script&gt; &lt;b&gt;</title>"),
            std::string::npos);
  EXPECT_TRUE(page.note.empty());
  EXPECT_EQ(page.points, 600);
  EXPECT_EQ(page.points_kept, 600);
  EXPECT_EQ(page.triangles_kept, mesh.num_faces());

  // Positions in the axis frame: x axial (z here), y along u (world x, the axis least aligned
  // with z), z along v = d x u (world y).
  const std::vector<float> pos = floats(string_field(h, "positions"));
  ASSERT_EQ(pos.size(), 3u * 600);
  for (int c = 0; c < 3; ++c) {
    for (int i : {0, 77, 199}) {
      const Vec3& p = plan.circuits[c].points[i].position;
      const int k = 3 * (200 * c + i);
      EXPECT_NEAR(pos[k], p.z(), 1e-4 * (1 + std::fabs(p.z())));
      EXPECT_NEAR(pos[k + 1], p.x(), 1e-4 * 50);
      EXPECT_NEAR(pos[k + 2], p.y(), 1e-4 * 50);
    }
  }
  const std::vector<float> st = floats(string_field(h, "states"));
  ASSERT_EQ(st.size(), 14u * motion.states.size());
  EXPECT_NEAR(st[14 * (motion.states.size() - 1)], motion.wind_time, 1e-3 * motion.wind_time);
  EXPECT_EQ(floats(string_field(h, "mesh_triangles")).size(), 3u * mesh.num_faces());
}

// A robot cell's page: the joints block and the joint panel's script are added, the data read
// back matches the joints given (per machine state: its joints.csv row, planned time, robot time
// and values); the same plan without joints is the page as before, byte for byte, with neither.
TEST(ViewerPage, RobotJointsAddTheJointPanel) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 200, 3);
  const Mesh mesh(test::open_cylinder(50, 700, 24, 10));
  const MachineOptions machine;
  const Motion motion = compute_motion(plan, machine);
  const int n = static_cast<int>(motion.states.size());
  ViewerJoints joints;
  joints.arm = "test arm";
  joints.series.resize(7);
  for (int j = 0; j < 7; ++j) {
    joints.series[j].name = j == 0 ? "E1" : "A" + std::to_string(j);
    if (j > 0) {
      joints.series[j].min = -170;
      joints.series[j].max = 170;
    }
  }
  for (int i = 0; i < n; ++i) {
    joints.time.push_back(0.5 * i);
    for (int j = 0; j < 7; ++j) joints.series[j].values.push_back(10.0 * j + 0.01 * i);
  }
  const ViewerPage plain = viewer_page(plan, mesh, motion);
  const ViewerPage robot = viewer_page(plan, mesh, motion, {}, &joints);
  EXPECT_EQ(viewer_page(plan, mesh, motion, {}, nullptr).html, plain.html);
  EXPECT_EQ(plain.html.find("windplan-joints"), std::string::npos);
  const std::string& h = robot.html;
  EXPECT_EQ(count(h, "</script>"), 5);  // data, joints, three.js, the viewer, the joint panel
  EXPECT_EQ(count(h, "<script id=\"windplan-joints\" type=\"application/json\">"), 1);
  EXPECT_NE(h.find("windplan-viewer: joints panel"), std::string::npos);
  EXPECT_NE(h.find("\"arm\":\"test arm\""), std::string::npos);
  EXPECT_NE(h.find("\"names\":[\"E1\",\"A1\",\"A2\",\"A3\",\"A4\",\"A5\",\"A6\"]"),
            std::string::npos);
  EXPECT_NE(h.find("\"limited\":[false,true,true,true,true,true,true]"), std::string::npos);
  const std::vector<float> t = floats(string_field(h, "state_t"));
  const std::vector<float> v = floats(string_field(h, "values"));
  const std::vector<unsigned char> rows = unbase64(string_field(h, "rows"));
  ASSERT_EQ(t.size(), static_cast<std::size_t>(n));  // not decimated: every state
  ASSERT_EQ(v.size(), 8u * n);
  ASSERT_EQ(rows.size(), 4u * n);
  for (int i : {0, n / 3, n - 1}) {
    std::uint32_t row = 0;
    std::memcpy(&row, &rows[4 * i], 4);
    EXPECT_EQ(row, static_cast<std::uint32_t>(i));
    EXPECT_FLOAT_EQ(t[i], static_cast<float>(motion.states[i].t_s));
    EXPECT_FLOAT_EQ(v[8 * i], static_cast<float>(0.5 * i));
    for (int j = 0; j < 7; ++j) EXPECT_FLOAT_EQ(v[8 * i + 1 + j], float(10.0 * j + 0.01 * i));
  }
  // One value too few: refused.
  joints.series[3].values.pop_back();
  EXPECT_THROW(viewer_page(plan, mesh, motion, {}, &joints), InputError);
}

TEST(ViewerPage, MeasuredCoverageInThePanel) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 50, 1);
  const Mesh mesh(test::open_cylinder(50, 700, 8, 4));
  EXPECT_EQ(viewer_page(plan, mesh, Motion{}).html.find("\"coverage\":"), std::string::npos);
  plan.metrics.geodesic_turn_limit = 1.0;  // a shape of revolution: stations in mm
  StationCoverage st;
  st.station = 120;
  st.bare_fraction = 0.0125;
  st.widest_gap = 2.5;
  plan.metrics.coverage.stations = {st};
  const std::string h = viewer_page(plan, mesh, Motion{}).html;
  EXPECT_NE(h.find("\"coverage\":"), std::string::npos);
  EXPECT_NE(h.find("[\"at 120.0 mm\",\"bare 1.25%, gap 2.5 mm, 0.00 plies\"]"), std::string::npos);
  // Off a shape of revolution the stations are levels of the harmonic height.
  plan.metrics.geodesic_turn_limit = std::nan("");
  plan.metrics.coverage.stations[0].station = 0.25;
  EXPECT_NE(viewer_page(plan, mesh, Motion{}).html.find("[\"at h = 0.250\","), std::string::npos);
}

TEST(ViewerPage, LargePlanIsDecimatedUnderTheLimitWithANote) {
  // 4 circuits of 150000 points: about 25 MB of point data before decimation.
  WindingPlan plan = test::helix_plan(50, 40, 20, 150000, 4);
  plan.metrics.band_width = 6;
  const Mesh mesh(test::open_cylinder(50, 700, 24, 10));
  ViewerOptions o;
  o.max_bytes = 3000000;
  const ViewerPage page = viewer_page(plan, mesh, Motion{}, o);
  EXPECT_LE(page.html.size(), o.max_bytes);
  EXPECT_EQ(page.points, 600000);
  EXPECT_LT(page.points_kept, 600000);
  EXPECT_GT(page.points_kept, 600000 / 40);
  EXPECT_FALSE(page.note.empty());
  EXPECT_NE(page.html.find(page.note), std::string::npos);
  // Every circuit keeps its ends.
  const std::vector<float> pos = floats(string_field(page.html, "positions"));
  ASSERT_EQ(pos.size(), 3u * page.points_kept);
  const Vec3& last = plan.circuits.back().points.back().position;
  EXPECT_NEAR(pos[pos.size() - 3], last.z(), 1e-3 * last.z());
  EXPECT_EQ(page.html.rfind("</html>\n"), page.html.size() - 8);
}

TEST(ViewerPage, HugeMandrelIsClustered) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 200, 1);
  const Mesh mesh(test::open_cylinder(50, 700, 600, 400));  // 480000 triangles
  ViewerOptions o;
  o.max_bytes = 2500000;
  const ViewerPage page = viewer_page(plan, mesh, Motion{}, o);
  EXPECT_LE(page.html.size(), o.max_bytes);
  EXPECT_LT(page.triangles_kept, page.triangles);
  EXPECT_GT(page.triangles_kept, 1000);
  EXPECT_NE(page.note.find("triangles"), std::string::npos);
}

TEST(ViewerPage, BadOptions) {
  ViewerOptions o;
  o.max_bytes = 100000;
  std::string why;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("max_bytes"), std::string::npos);
  const WindingPlan plan = test::helix_plan(50, 40, 1.5, 20, 1);
  EXPECT_THROW(viewer_page(plan, Mesh(test::open_cylinder(50, 700, 8, 4)), Motion{}, o),
               InputError);
}

}  // namespace
}  // namespace windplan
