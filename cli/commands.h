#pragma once
// The windplan subcommands. Each takes its arguments (after the subcommand name) and returns the
// process exit code; user errors are thrown as windplan exceptions and mapped to exit codes in
// main(). Each has a one-line summary and a --help text.
#include <string>
#include <vector>

namespace windplan::cli {

struct Command {
  const char* name;
  const char* summary;
  const char* help;  // full usage text printed by "windplan <name> --help"
  int (*run)(const std::vector<std::string>& args);
};

/// All subcommands, in the order --help lists them.
const std::vector<Command>& commands();

// One function per subcommand, each in its own cmd_<name>.cpp.

/// cmd_mandrel.cpp: build a job's mandrel and report it.
int run_mandrel(const std::vector<std::string>& args);
extern const char* const kMandrelHelp;

/// cmd_mesh.cpp: load, check, repair and write a mesh file or a job's mesh mandrel.
int run_mesh(const std::vector<std::string>& args);
extern const char* const kMeshHelp;

/// cmd_girth.cpp: the girth field of a job's winding surface (planner/girth/girth.h).
int run_girth(const std::vector<std::string>& args);
extern const char* const kGirthHelp;

/// cmd_geodesic.cpp: a geodesic between two surface points (geodesic) and a closed geodesic loop
/// refined from a curve (loop), under a Euclidean, density or anisotropic metric.
int run_geodesic(const std::vector<std::string>& args);
extern const char* const kGeodesicHelp;
int run_loop(const std::vector<std::string>& args);
extern const char* const kLoopHelp;

/// cmd_cutline.cpp: coplanar cut-lines of a job (its cutlines: list) or from flags, on a job's
/// winding surface or a mesh file (planner/cutlines/cutlines.h).
int run_cutline(const std::vector<std::string>& args);
extern const char* const kCutlineHelp;

/// cmd_helices.cpp: plan a job's helices and circuits and report passes and plan metrics.
int run_helices(const std::vector<std::string>& args);
extern const char* const kPatternsHelp;
int run_patterns(const std::vector<std::string>& args);
extern const char* const kHelicesHelp;

/// cmd_run.cpp: run a job end to end (mandrel -> girth -> helices -> toolpath -> exports).
int run_run(const std::vector<std::string>& args);
extern const char* const kRunHelp;
int run_simulate(const std::vector<std::string>& args);
extern const char* const kSimulateHelp;

/// cmd_check_fea.cpp: solve a design job's structural model with CalculiX and check its plies.
int run_check_fea(const std::vector<std::string>& args);
extern const char* const kCheckFeaHelp;

}  // namespace windplan::cli
