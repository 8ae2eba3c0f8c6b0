#include "cli/commands.h"

namespace windplan::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"mandrel", "build a job's mandrel (mesh, CAD or parametric) and report it", kMandrelHelp,
       run_mandrel},
      {"mesh", "check a mesh (or a job's mesh mandrel), repair it, convert it", kMeshHelp,
       run_mesh},
      {"helices", "plan a job's equally spaced geodesic helices and report the plan metrics",
       kHelicesHelp, run_helices},
      {"patterns", "list the winding patterns that close near a job's winding, measured",
       kPatternsHelp, run_patterns},
      {"run", "run a job end to end: mandrel, girth, helices, toolpath, every output file",
       kRunHelp, run_run},
      {"simulate", "replay a G-code program through the job's machine: deviation, limits, time",
       kSimulateHelp, run_simulate},
      {"check-fea",
       "solve a design job's structural model (model.inp) with CalculiX: first-ply failure",
       kCheckFeaHelp, run_check_fea},
      {"girth", "the girth field of a job's winding surface (shortest loops winding once)",
       kGirthHelp, run_girth},
      {"geodesic", "a geodesic between two surface points (vertex or x,y,z), optional metric",
       kGeodesicHelp, run_geodesic},
      {"loop", "refine a closed curve into a closed geodesic loop, optional metric", kLoopHelp,
       run_loop},
      {"cutline", "coplanar cut-lines: the shortest planar trim loop near a plane or station",
       kCutlineHelp, run_cutline},
  };
  return list;
}

}  // namespace windplan::cli
