// windplan run's output folder as a subprocess (export/files/output_set.h): a run killed during
// export leaves the previous complete set, two runs into one folder (one refused), the manifest's
// hashes against sha256sum, no file of another job left beside a new set; and the bad inputs of
// issue 18 that only the whole program shows (name escaping out/, garbage echoed, warnings).
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/cli_runner.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;
using test::CliTest;
using test::slurp;

/// A windplan run started with WINDPLAN_TEST_PAUSE_AFTER=<pause_after>, stopped at that point.
class PausedRun {
 public:
  PausedRun(const std::vector<std::string>& args, const std::string& pause_after,
            const fs::path& err_file) {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::setenv("WINDPLAN_TEST_PAUSE_AFTER", pause_after.c_str(), 1);
      const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int null = ::open("/dev/null", O_RDWR);
      ::dup2(null, 0);
      ::dup2(null, 1);
      ::dup2(err, 2);
      std::vector<char*> argv;
      std::string bin = WINDPLAN_BINARY;
      argv.push_back(bin.data());
      std::vector<std::string> copy = args;
      for (std::string& a : copy) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(bin.c_str(), argv.data());
      ::_exit(127);
    }
    // Wait for the pause line (the run plans first: seconds), or for the child to end.
    const std::string line = "windplan: test pause after " + pause_after;
    for (;;) {
      if (slurp(err_file).find(line) != std::string::npos) {
        paused_ = true;
        break;
      }
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        break;
      }
      ::usleep(20000);
    }
  }
  ~PausedRun() { stop(SIGKILL); }
  bool paused() const { return paused_; }
  pid_t pid() const { return pid_; }
  /// Sends `sig` and reaps the child; returns its terminating signal (0 if it exited).
  int stop(int sig) {
    if (pid_ <= 0) return 0;
    ::kill(pid_, sig);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  }

 private:
  pid_t pid_ = -1;
  bool paused_ = false;
};

std::map<std::string, std::string> folder_contents(const fs::path& d) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::directory_iterator(d)) m[e.path().filename().string()] = slurp(e.path());
  return m;
}

std::set<std::string> names_in(const fs::path& d) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(d)) s.insert(e.path().filename().string());
  return s;
}

std::string sha256sum(const fs::path& p) {
  std::string out(64, '\0');
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(
      ::popen(("sha256sum " + test::shell_quote(p.string())).c_str(), "r"), ::pclose);
  if (!pipe || std::fread(out.data(), 1, 64, pipe.get()) != 64) return "";
  return out;
}

// Every {"name": n, "size": s, "sha256": h} of the manifest's "files", read independently of
// export/files/manifest.cpp (a plain scan of the text).
std::vector<std::array<std::string, 3>> manifest_files(const std::string& json) {
  std::vector<std::array<std::string, 3>> out;
  std::size_t pos = json.find("\"files\"");
  auto field = [&](const std::string& key, std::size_t from, std::size_t* end) {
    const std::size_t a = json.find("\"" + key + "\": ", from) + key.size() + 4;
    std::size_t b = a;
    while (b < json.size() && json[b] != ',' && json[b] != '}') ++b;
    *end = b;
    std::string v = json.substr(a, b - a);
    if (!v.empty() && v.front() == '"') v = v.substr(1, v.size() - 2);
    return v;
  };
  while ((pos = json.find("{\"name\"", pos)) != std::string::npos) {
    std::size_t end = pos;
    std::array<std::string, 3> e;
    e[0] = field("name", pos, &end);
    e[1] = field("size", end, &end);
    e[2] = field("sha256", end, &end);
    out.push_back(e);
    pos = end;
  }
  return out;
}

fs::path config(const std::string& name) { return test::source_dir() / "configs" / name; }

class CliOutputSet : public CliTest {
 protected:
  // A second job into the same folder: another name and G-code dialect (toolpath.gcode).
  fs::path marlin_job() const {
    const fs::path p = dir_ / "marlin.yaml";
    std::ofstream(p)
        << "name: marlin_pipe\nmandrel: {source: pipe, pipe: {radius: 40, length: 300}}\n"
           "machine: {gcode: {dialect: marlin}}\nwinding: {turns: 2, circuits: 3}\n";
    return p;
  }
};

TEST_F(CliOutputSet, ManifestHashesAndSizesMatchTheFiles) {
  const fs::path out = dir_ / "set";
  const test::RunResult r = run({"run", config("pipe.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string man = slurp(out / "manifest.json");
  const auto files = manifest_files(man);
  std::set<std::string> listed = {"manifest.json"};
  for (const auto& [name, size, hash] : files) {
    listed.insert(name);
    EXPECT_EQ(hash, sha256sum(out / name)) << name;
    EXPECT_EQ(size, std::to_string(fs::file_size(out / name))) << name;
  }
  EXPECT_EQ(listed, names_in(out)) << man;
  EXPECT_GE(files.size(), 9u);
  // The job file's own hash, and the version.
  EXPECT_NE(man.find(sha256sum(config("pipe.yaml"))), std::string::npos) << man;
  EXPECT_NE(man.find("\"windplan_version\": \""), std::string::npos) << man;
}

TEST_F(CliOutputSet, AnotherJobsFilesAreNotLeftBesideTheNewSet) {
  const fs::path out = dir_ / "set";
  ASSERT_EQ(run({"run", marlin_job().string(), "--out", out.string()}).code, 0);
  ASSERT_TRUE(fs::exists(out / "toolpath.gcode"));
  const test::RunResult r = run({"run", config("pipe.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / "toolpath.gcode"));  // once left beside the new toolpath.ngc
  EXPECT_TRUE(fs::exists(out / "toolpath.ngc"));
  EXPECT_EQ(names_in(dir_).count(".set.lock"), 0u);  // removed by its holder (issue 28)
  for (const std::string& n : names_in(dir_))
    EXPECT_EQ(n.find(".set.staging"), std::string::npos) << n;
}

TEST_F(CliOutputSet, RunKilledDuringExportLeavesThePreviousCompleteSetAndNoTempFile) {
  const fs::path out = dir_ / "set";
  ASSERT_EQ(run({"run", marlin_job().string(), "--out", out.string()}).code, 0);
  const auto before = folder_contents(out);
  for (const char* point : {"payout.csv", "report.json", "swap"}) {
    PausedRun p({"run", config("pipe.yaml").string(), "--out", out.string()}, point,
                dir_ / "paused_err.txt");
    ASSERT_TRUE(p.paused()) << slurp(dir_ / "paused_err.txt");
    EXPECT_EQ(p.stop(SIGKILL), SIGKILL);
    EXPECT_EQ(folder_contents(out), before) << "killed after " << point;
    for (const std::string& n : names_in(out)) EXPECT_EQ(n.find(".tmp"), std::string::npos) << n;
  }
  // A SIGKILL cannot be caught: its staging folder stays beside the set until the next run into
  // the folder removes it.
  const test::RunResult r = run({"run", config("pipe.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(names_in(dir_).count("set"), 1u);
  for (const std::string& n : names_in(dir_)) EXPECT_EQ(n.find("staging"), std::string::npos) << n;
  EXPECT_FALSE(fs::exists(out / "toolpath.gcode"));
}

TEST_F(CliOutputSet, RunStoppedByACatchableSignalRemovesItsTemporaryFiles) {
  const fs::path out = dir_ / "set";
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    PausedRun p({"run", config("pipe.yaml").string(), "--out", out.string()}, "payout.csv",
                dir_ / "paused_err.txt");
    ASSERT_TRUE(p.paused()) << slurp(dir_ / "paused_err.txt");
    EXPECT_EQ(p.stop(sig), sig);
    EXPECT_EQ(names_in(dir_).count("set"), 0u) << sig;  // no set was ever complete
    for (const std::string& n : names_in(dir_))
      EXPECT_EQ(n.find("staging"), std::string::npos) << n;
  }
}

TEST_F(CliOutputSet, SecondRunIntoAHeldFolderIsRefused) {
  const fs::path out = dir_ / "set";
  PausedRun first({"run", config("pipe.yaml").string(), "--out", out.string()}, "fibre_path.csv",
                  dir_ / "paused_err.txt");
  ASSERT_TRUE(first.paused()) << slurp(dir_ / "paused_err.txt");
  const test::RunResult second = run({"run", marlin_job().string(), "--out", out.string()});
  EXPECT_EQ(second.code, 1) << second.err;
  EXPECT_NE(second.err.find("another windplan run (pid " + std::to_string(first.pid()) + ")"),
            std::string::npos)
      << second.err;
  first.stop(SIGKILL);
  EXPECT_EQ(run({"run", marlin_job().string(), "--out", out.string()}).code, 0);
}

// Issue 28: a forged manifest.json listing a user's file (its true size and hash) made `run`
// delete it. Every shipped job, into a folder holding a user's file, a report.md of theirs and
// such a manifest: refused at once naming the file, everything kept, no lock file left.
TEST_F(CliOutputSet, EveryShippedJobRefusesAFolderWithAForgedManifest) {
  const fs::path out = dir_ / "documents";
  fs::create_directories(out);
  std::ofstream(out / "thesis.docx") << "chapter 1\n";
  std::ofstream(out / "report.md") << "my report\n";
  const std::string forged =
      "{\n  \"windplan_manifest\": 1,\n  \"windplan_version\": \"0.1.0\",\n  \"job\": \"x\",\n"
      "  \"inputs\": [],\n  \"files\": [\n    {\"name\": \"thesis.docx\", \"size\": 10, "
      "\"sha256\": \"" +
      sha256sum(out / "thesis.docx") +
      "\"},\n    {\"name\": \"report.md\", \"size\": 10, "
      "\"sha256\": \"" +
      sha256sum(out / "report.md") + "\"}\n  ]\n}\n";
  std::ofstream(out / "manifest.json") << forged;
  const auto before = folder_contents(out);
  int jobs = 0;
  for (const auto& e : fs::directory_iterator(test::source_dir() / "configs")) {
    if (e.path().extension() != ".yaml") continue;
    ++jobs;
    const test::RunResult r = run({"run", e.path().string(), "--out", out.string()});
    EXPECT_EQ(r.code, 1) << e.path() << r.err;
    EXPECT_NE(r.err.find("did not write: thesis.docx (listed, but not a name windplan writes)"),
              std::string::npos)
        << e.path() << r.err;
    EXPECT_EQ(r.err.find("done in"), std::string::npos) << "planned first: " << r.err;
    EXPECT_EQ(folder_contents(out), before) << e.path();
    EXPECT_EQ(names_in(dir_), (std::set<std::string>{"documents", "out.txt", "err.txt"}));
  }
  EXPECT_GE(jobs, 10);
}

TEST_F(CliOutputSet, AnEmptyOrLinkedOutIsRefusedBeforePlanning) {
  test::RunResult r = run({"run", config("pipe.yaml").string(), "--out", ""});
  EXPECT_EQ(r.code, 2) << r.err;  // was exit 3, internal error
  EXPECT_NE(r.err.find("--out needs a folder name"), std::string::npos) << r.err;
  r = run({"run", config("pipe.yaml").string(), "--threads", "100000"});
  EXPECT_EQ(r.code, 2) << r.err;  // was "expects an integer >= 1"
  EXPECT_NE(r.err.find("--threads expects an integer from 1 to 4096, got '100000' (more threads"),
            std::string::npos)
      << r.err;
  fs::create_symlink(dir_ / "gone", dir_ / "dangling");
  r = run({"run", config("pipe.yaml").string(), "--out", (dir_ / "dangling").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("dangling: is a symbolic link to nothing"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("done in"), std::string::npos) << "planned first: " << r.err;
}

TEST_F(CliOutputSet, JobNameCannotEscapeTheOutputFolder) {
  const fs::path job = dir_ / "jobs" / "j.yaml";
  fs::create_directories(job.parent_path());
  std::ofstream(job)
      << "name: \"../../escape\"\nmandrel: {source: pipe, pipe: {radius: 50, length: 500}}\n";
  const test::RunResult r = run({"run", job.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("key 'name': must not contain '..'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(fs::current_path() / ".." / "escape"));
}

TEST_F(CliOutputSet, GarbageFromAMeshFileIsNeverEchoedRaw) {
  const fs::path off = dir_ / "garbage.off";
  std::ofstream(off, std::ios::binary) << "OFF\n4 4 0\n0 0 0\n1 0 \x1b[31mRED\x1b[0m 0\n\xff\xfe\n";
  const test::RunResult r = run({"mesh", off.string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\xff'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\\x1b[31mRED"), std::string::npos) << r.err;
}

TEST_F(CliOutputSet, CoarseRemeshWarnsWithTheAreaChange) {
  const fs::path job = dir_ / "coarse.yaml";
  std::ofstream(job)
      << "mandrel: {source: pipe, remesh: 50, pipe: {radius: 50, length: 500}}\n"
         "winding: {turns: 2, circuits: 2}\noutput: {csv: false, ply: false, svg: false}\n";
  // (windplan mandrel: on this coarse mesh the pipe's waist falls below the turnaround radius,
  // so `run` stops in the planner after the mandrel stage.)
  const test::RunResult r = run({"mandrel", job.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  // (The sign depends on the triangles the remesher makes: chords inside the pipe lose area,
  // triangles across its rims can gain it.)
  EXPECT_NE(r.err.find("warning: remesh = 50 mm changed the mandrel's area by "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("more than 1 %): use a smaller mandrel.remesh"), std::string::npos)
      << r.err;
}

TEST_F(CliOutputSet, AutoCircuitsOverflowOnAMeshMandrelIsRefused) {
  // band_width: 1e-9 once overflowed planner/winding/helix.cpp's int conversion into 1 circuit,
  // exit 0. A mesh mandrel's size is known only once read, so the pipeline checks it then
  // (helix.cpp keeps a guard at the conversion).
  const fs::path job = dir_ / "tiny_band.yaml";
  std::ofstream(job) << "mandrel: {source: mesh, file: "
                     << (test::source_dir() / "configs/meshes/tube.obj").string()
                     << "}\nwinding: {band_width: 0.005}\n";
  const test::RunResult r = run({"run", job.string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("key 'winding.band_width' = 0.005 mm gives about 6.283e+04 circuits"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("above the bound 10000"), std::string::npos) << r.err;
}

TEST_F(CliOutputSet, CadMandrelDeflectionsAreCheckedOnceTheModelIsRead) {
  // The STEP vessel is 303.5 mm across: 0.002 mm is below 1e-5 of it (OCCT took gigabytes).
  const fs::path job = dir_ / "cad.yaml";
  std::ofstream(job) << "mandrel: {source: cad, file: "
                     << (test::source_dir() / "configs/mandrels/vessel.step").string()
                     << ", linear_deflection: 0.002}\n";
  const test::RunResult r = run({"run", job.string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("key 'mandrel.linear_deflection' = 0.002 mm is below the bound"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

}  // namespace
}  // namespace windplan
