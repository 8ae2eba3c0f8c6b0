// viewer.html in a real browser: `windplan run` writes the page of a shipped job, headless
// Chromium (Debian's `chromium`, README set-up) loads it from disk with SwiftShader WebGL, and
// the test reads the screenshot and the console:
//   - the page logged its first frame and no error (its own "windplan-viewer ERROR" lines, any
//     "Uncaught" exception, WebGL errors);
//   - the mandrel (neutral grey) and the bands (saturated colours) cover parts of the 3-D view,
//     counted by colour class in the screenshot;
//   - moving the time slider (URL hash t=) changes the picture: few band pixels near the start,
//     many at the end;
//   - a robot job's joint panel shows, at the slider's moment, the joints joints.csv holds.
// The screenshots stay in build/screenshots/ for a person to look at.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "export/plots/viewer.h"
#include "geometry/base/atomic_file.h"
#include "tests/cli/cli_runner.h"
#include "tests/export/plan_fixtures.h"
#include "tests/export/png_image.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& p) { return test::slurp(p); }
std::string sh(const std::string& s) { return test::shell_quote(s); }

constexpr int kWidth = 1280, kHeight = 800;
constexpr int kPanel = 340;  // px: the panel on the right (viewer_app.js / viewer.cpp style)

struct Shot {
  test::RgbaImage image;
  std::string console;  // the page's console lines
};

struct Counts {
  long view = 0, background = 0, grey = 0, colour = 0;
};

// Colour classes of the 3-D view (left of the panel): the clear colour #e9edf2, the mandrel's
// neutral grey (shaded), the bands' saturated colours.
Counts classify(const test::RgbaImage& im) {
  Counts c;
  for (int y = 0; y < im.height - 24; ++y) {  // the hint line at the bottom is left out
    for (int x = 0; x < std::min(im.width, kWidth - kPanel); ++x) {
      const std::uint8_t* p = im.at(x, y);
      const int r = p[0], g = p[1], b = p[2];
      const int mx = std::max({r, g, b}), mn = std::min({r, g, b});
      ++c.view;
      if (std::abs(r - 0xe9) <= 4 && std::abs(g - 0xed) <= 4 && std::abs(b - 0xf2) <= 4)
        ++c.background;
      else if (mx - mn <= 14 && mx >= 50 && mx <= 235)
        ++c.grey;
      else if (mx - mn >= 70 && (mx - mn) * 10 >= 4 * mx)
        ++c.colour;
    }
  }
  return c;
}

long differing_pixels(const test::RgbaImage& a, const test::RgbaImage& b) {
  long n = 0;
  for (int y = 0; y < std::min(a.height, b.height); ++y)
    for (int x = 0; x < std::min(a.width, b.width) - kPanel; ++x) {
      const std::uint8_t *p = a.at(x, y), *q = b.at(x, y);
      if (std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) > 30) ++n;
    }
  return n;
}

class ViewerBrowser : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::system("command -v chromium >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "chromium is not installed (README set-up installs it)";
    dir_ = fs::temp_directory_path() /
           ("windplan_browser_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    fs::create_directories(WINDPLAN_SCREENSHOTS);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  /// Runs the job into dir_/out; returns the page's path.
  fs::path run_job(const std::string& config) {
    const fs::path out = dir_ / "out";
    const std::string cmd = sh(WINDPLAN_BINARY) + " run " +
                            sh(std::string(WINDPLAN_SOURCE_DIR) + "/configs/" + config) +
                            " --out " + sh(out.string()) + " >" + sh((dir_ / "run.txt").string()) +
                            " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << read_all(dir_ / "run.txt");
    return out / "viewer.html";
  }

  /// Loads page#hash in headless Chromium; the screenshot goes to build/screenshots/<name>.png.
  Shot shoot(const fs::path& page, const std::string& hash, const std::string& name) {
    const fs::path png = fs::path(WINDPLAN_SCREENSHOTS) / (name + ".png");
    const fs::path log = dir_ / (name + ".log");
    fs::remove(png);
    const std::string url = "file://" + fs::absolute(page).string() + "#" + hash;
    const std::string cmd =
        "timeout 300 chromium --headless=new --no-sandbox --use-angle=swiftshader "
        "--enable-unsafe-swiftshader --hide-scrollbars --no-first-run --user-data-dir=" +
        sh((dir_ / ("profile_" + name)).string()) + " --window-size=" + std::to_string(kWidth) +
        "," + std::to_string(kHeight) + " --screenshot=" + sh(png.string()) +
        " --enable-logging=stderr --v=0 --virtual-time-budget=20000 " + sh(url) + " >/dev/null 2>" +
        sh(log.string());
    const int rc = std::system(cmd.c_str());
    Shot s;
    std::istringstream lines(read_all(log));
    for (std::string line; std::getline(lines, line);)
      if (line.find("CONSOLE") != std::string::npos) s.console += line + "\n";
    EXPECT_EQ(rc, 0) << "chromium failed; its log:\n" << read_all(log);
    std::string why;
    EXPECT_TRUE(test::read_png(png.string(), &s.image, &why)) << why;
    return s;
  }

  // The band segments drawn, from the page's frame line.
  static long segments(const Shot& s) {
    const auto p = s.console.find("segments=");
    return p == std::string::npos ? -1 : std::stol(s.console.substr(p + 9));
  }

  static void expect_clean(const Shot& s, const std::string& frame_line) {
    EXPECT_NE(s.console.find("windplan-viewer: frame " + frame_line), std::string::npos)
        << "no frame logged; console:\n"
        << s.console;
    EXPECT_EQ(s.console.find("windplan-viewer ERROR"), std::string::npos) << s.console;
    EXPECT_EQ(s.console.find("Uncaught"), std::string::npos) << s.console;
    EXPECT_EQ(s.console.find("GL_INVALID"), std::string::npos) << s.console;
    EXPECT_EQ(s.console.find("WebGL: INVALID"), std::string::npos) << s.console;
  }

  // PNG renders of the job's plots (rsvg-convert, README set-up) for a person to look at; each
  // must read back as a PNG of the SVG's size with some colour in it.
  void render_plots(const fs::path& out, const std::string& name) {
    if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) {
      std::printf("rsvg-convert is not installed: no PNG renders\n");
      return;
    }
    for (const char* plot : {"development", "axes"}) {
      const fs::path png = fs::path(WINDPLAN_SCREENSHOTS) / (name + "_" + plot + ".png");
      const std::string cmd = "rsvg-convert " + sh((out / (std::string(plot) + ".svg")).string()) +
                              " -o " + sh(png.string());
      EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
      test::RgbaImage im;
      std::string why;
      ASSERT_TRUE(test::read_png(png.string(), &im, &why)) << why;
      long coloured = 0;
      for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
          const std::uint8_t* p = im.at(x, y);
          coloured += std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 60;
        }
      EXPECT_GT(coloured, 2000) << png;
    }
  }

  // The checks shared by the jobs: first and last moments, and one other colour mode.
  fs::path check_job(const std::string& config, const std::string& name) {
    const fs::path page = run_job(config);
    render_plots(page.parent_path(), name);
    EXPECT_TRUE(fs::exists(page));
    EXPECT_LT(fs::file_size(page), 5000000u);
    const Shot early = shoot(page, "t=0.02", name + "_t0.02");
    const Shot full = shoot(page, "t=1", name + "_t1");
    const Shot slip = shoot(page, "t=1&mode=slippage", name + "_slippage");
    expect_clean(early, "t=0.020");
    expect_clean(full, "t=1.000");
    expect_clean(slip, "t=1.000 segments=");
    EXPECT_NE(slip.console.find("mode=slippage"), std::string::npos) << slip.console;
    const Shot machine = shoot(page, "t=0.5&frame=machine", name + "_machine_frame");
    expect_clean(machine, "t=0.500");
    EXPECT_NE(machine.console.find("frame=machine"), std::string::npos) << machine.console;
    // The slider draws the winding in order: more band segments later.
    EXPECT_GT(segments(early), 0);
    EXPECT_LT(segments(early), segments(machine));
    EXPECT_LT(segments(machine), segments(full));
    const Counts ce = classify(early.image), cf = classify(full.image);
    std::printf(
        "%s: view %ld px; t=0.02: background %ld, mandrel grey %ld, band colour %ld; "
        "t=1: background %ld, grey %ld, colour %ld; %ld px differ\n",
        name.c_str(), ce.view, ce.background, ce.grey, ce.colour, cf.background, cf.grey, cf.colour,
        differing_pixels(early.image, full.image));
    // The mandrel is drawn: near the start most of it is bare.
    EXPECT_GT(ce.grey, ce.view / 20);
    // The bands are drawn at the end, over a good part of the mandrel's grey.
    EXPECT_GT(cf.colour, ce.view / 50);
    EXPECT_GT(cf.colour, ce.colour + ce.view / 50);  // (a layup winds a whole hoop layer first)
    EXPECT_LT(cf.grey, ce.grey);
    // The slider changed the picture.
    EXPECT_GT(differing_pixels(early.image, full.image), ce.view / 50);
    // The page fills the view: not all background.
    EXPECT_LT(ce.background, ce.view * 9 / 10);
    return page;
  }

  fs::path dir_;
};

// The joint panel's line at slider fraction t ("windplan-viewer: joints t=0.250 row=R t_robot=S
// E1=.. A1=.. ..."): the joints.csv row and every name=value; row -1 when absent.
struct JointLine {
  long row = -1;
  std::map<std::string, double> value;  // t_robot and the joints
};

JointLine joint_line(const std::string& console, const std::string& t) {
  JointLine out;
  const std::string key = "windplan-viewer: joints t=" + t + " ";
  const std::size_t p = console.find(key);
  if (p == std::string::npos) return out;
  std::istringstream in(console.substr(p + key.size(), console.find('"', p) - p - key.size()));
  for (std::string tok; in >> tok;) {
    const std::size_t eq = tok.find('=');
    if (eq == std::string::npos) continue;
    if (tok.substr(0, eq) == "row")
      out.row = std::stol(tok.substr(eq + 1));
    else
      out.value[tok.substr(0, eq)] = std::stod(tok.substr(eq + 1));
  }
  return out;
}

// The rows of a CSV file windplan wrote (numbers only, after the header).
std::vector<std::vector<double>> csv_rows(const fs::path& file) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(read_all(file));
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> r;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) r.push_back(std::stod(c));
    rows.push_back(r);
  }
  return rows;
}

TEST_F(ViewerBrowser, Vessel) {
  const fs::path page = check_job("vessel.yaml", "vessel");
  // A lathe job's page has no joint panel.
  EXPECT_EQ(read_all(page).find("windplan-joints"), std::string::npos);
}

// A robot cell (the shipped bent tube on the KR 16-2 cell): the joint panel is built, and at two
// moments of the slider it shows the joints of the state viewer_app.js shows, read back against
// joints.csv (its row: E1, A1..A6 and the robot's time) and axes.csv (the state's planned time is
// at or before the slider's moment); the values change with the slider.
TEST_F(ViewerBrowser, BentTube) {
  const fs::path page = check_job("bent_tube.yaml", "bent_tube");
  const std::vector<std::vector<double>> joints = csv_rows(page.parent_path() / "joints.csv");
  const std::vector<std::vector<double>> axes = csv_rows(page.parent_path() / "axes.csv");
  ASSERT_EQ(joints.size(), axes.size());
  ASSERT_FALSE(axes.empty());
  const double wind_time = axes.back()[2];
  const char* names[7] = {"E1", "A1", "A2", "A3", "A4", "A5", "A6"};
  std::vector<JointLine> seen;
  for (const char* t : {"0.250", "0.750"}) {
    const Shot s = shoot(page, std::string("t=") + t, std::string("bent_tube_joints_t") + t);
    expect_clean(s, std::string("t=") + t);
    EXPECT_NE(s.console.find("windplan-viewer: joints panel E1,A1,A2,A3,A4,A5,A6"),
              std::string::npos)
        << s.console;
    const JointLine j = joint_line(s.console, t);
    ASSERT_GE(j.row, 0) << s.console;
    ASSERT_LT(j.row, static_cast<long>(joints.size()));
    const std::vector<double>& csv = joints[j.row];  // circuit, index, t_s, E1, A1..A6, S, T
    EXPECT_NEAR(j.value.at("t_robot"), csv[2], 2e-3);
    for (int k = 0; k < 7; ++k) EXPECT_NEAR(j.value.at(names[k]), csv[3 + k], 2e-3) << names[k];
    EXPECT_LE(axes[j.row][2], std::stod(t) * wind_time * (1 + 1e-6));
    EXPECT_GT(axes[j.row][2], std::stod(t) * wind_time - 0.01 * wind_time);
    std::printf("joint panel at t=%s: joints.csv row %ld, A1 %.3f A2 %.3f A3 %.3f deg\n", t, j.row,
                j.value.at("A1"), j.value.at("A2"), j.value.at("A3"));
    seen.push_back(j);
  }
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_LT(seen[0].row, seen[1].row);
  double moved = 0.0;
  for (const char* n : names) moved += std::fabs(seen[0].value.at(n) - seen[1].value.at(n));
  EXPECT_GT(moved, 1.0);  // deg, summed over the joints
}

// The layup job (planner/plan_layup.h): coloured by layer, with each layer named in the panel.
TEST_F(ViewerBrowser, VesselLayup) {
  const fs::path page = check_job("vessel_layup.yaml", "vessel_layup");
  const std::string html = read_all(page);
  for (const char* name : {"hoop1 (hoop", "helical1 (helical", "hoop2 (hoop", "helical2 (helical"})
    EXPECT_NE(html.find(name), std::string::npos) << name;
  const Shot s = shoot(page, "t=1&mode=layer", "vessel_layup_layers");
  expect_clean(s, "t=1.000");
  EXPECT_NE(s.console.find("mode=layer"), std::string::npos) << s.console;
  EXPECT_GT(classify(s.image).colour, classify(s.image).view / 20);
}

// A plan too large for the page: thinned, with the note in the panel, and still drawn.
TEST_F(ViewerBrowser, DecimatedPageStillDraws) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 60000, 4);
  plan.job_name = "large helix plan";
  plan.metrics.band_width = 20;
  const Mesh mesh(test::open_cylinder(50, 562, 48, 40));  // the helix rises 561.6 mm
  const MachineOptions machine;  // (named: GCC 12 warns maybe-uninitialized on the temporary)
  const Motion motion = compute_motion(plan, machine);
  ViewerOptions o;
  o.max_bytes = 2500000;
  const ViewerPage page = viewer_page(plan, mesh, motion, o);
  ASSERT_FALSE(page.note.empty());
  EXPECT_LT(page.points_kept, page.points);
  const fs::path file = dir_ / "viewer.html";
  write_text_atomically(file, page.html);
  EXPECT_LE(fs::file_size(file), o.max_bytes);
  const Shot s = shoot(file, "t=1", "decimated_t1");
  expect_clean(s, "t=1.000");
  const Counts c = classify(s.image);
  std::printf("decimated: %d of %d points, page %zu bytes; colour %ld px, grey %ld px\n",
              page.points_kept, page.points, page.html.size(), c.colour, c.grey);
  EXPECT_GT(c.colour, c.view / 50) << s.console;
}

}  // namespace
}  // namespace windplan
