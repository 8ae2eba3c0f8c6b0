// windplan check-fea <job.yaml> [--out DIR] [--fea DIR]
// Runs CalculiX on the structural model `windplan run` wrote for a job with a `design:` section
// (model.inp, export/files/fea_deck.h) and reads back per layer the fibre-direction strain and
// stress and the max-strain first-ply failure factor (export/files/ccx_results.h).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "export/files/ccx_results.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "planner/job/job.h"

namespace windplan::cli {

namespace fs = std::filesystem;

const char* const kCheckFeaHelp =
    "usage: windplan check-fea <job.yaml> [--out DIR] [--fea DIR]\n\n"
    "Solves the structural model of a job with a design: section with CalculiX and checks the\n"
    "laminate. `windplan run` writes model.inp and model_plies.csv into the job's output\n"
    "directory; check-fea copies them into the FEA folder (default: the output directory's\n"
    "name + '.fea', beside it), runs `ccx -i model` there (the Debian package calculix-ccx),\n"
    "reads model.dat and writes fea_check.md and fea_layers.csv: per layer the fibre-direction\n"
    "strain and stress (the mean over each ply's integration points, in the ply's own axes) and\n"
    "the first-ply failure factor by the maximum-strain criterion (fibre: fibre strength x V_f\n"
    "over E1; transverse: design.transverse_strength over E2; shear: design.shear_strength over\n"
    "G12; compression with the tensile allowables). A factor F >= 1 fails at the modelled\n"
    "pressure; the model is linear, so the first ply fails at pressure / F.\n"
    "The FEA folder holds only files check-fea writes (and ccx's): one holding anything else is\n"
    "refused.\n\n"
    "  --out DIR   the run's output directory (default as `windplan run`)\n"
    "  --fea DIR   the FEA folder (default: <output directory>.fea)\n";

namespace {

std::string quoted(const fs::path& p) {
  std::string s = "'";
  for (char c : p.string()) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return s + "'";
}

}  // namespace

int run_check_fea(const std::vector<std::string>& argv) {
  const Args args(argv, {}, {"--out", "-o", "--fea"});
  args.expect_positional(1, "a job file");
  const Job job = load_job(args.positional()[0]);
  if (!job.design.present) {
    throw ConfigError(job.path.string() +
                      ": check-fea needs a 'design:' section (the model "
                      "and its allowables come from it)");
  }
  if (std::isnan(job.design.fibre_strength)) {
    throw ConfigError(job.path.string() +
                      ": design.fibre_strength is needed for the failure check (MPa)");
  }
  fs::path dir = args.has("--out")               ? fs::path(args.value("--out"))
                 : args.has("-o")                ? fs::path(args.value("-o"))
                 : !job.output.directory.empty() ? job.output.directory
                                                 : fs::path("out") / job.name;
  const fs::path inp = dir / "model.inp", plies_csv = dir / "model_plies.csv";
  if (!fs::exists(inp) || !fs::exists(plies_csv)) {
    throw InputError(inp.string() + " is missing: run 'windplan run " + args.positional()[0] +
                     "' first");
  }
  const fs::path fea = args.has("--fea") ? fs::path(args.value("--fea"))
                                         : fs::path(dir.lexically_normal().string() + ".fea");
  const std::set<std::string> ours = {
      "model.inp", "model_plies.csv", "model.dat", "model.frd",    "model.sta",     "model.cvg",
      "model.12d", "spooles.out",     "ccx.log",   "fea_check.md", "fea_layers.csv"};
  if (fs::exists(fea)) {
    for (const auto& e : fs::directory_iterator(fea)) {
      if (!ours.count(e.path().filename().string())) {
        throw IoError(fea.string() + " holds " + e.path().filename().string() +
                      ", which check-fea did not write: give another folder with --fea");
      }
    }
  }
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
    throw IoError("ccx (CalculiX) is not installed: apt-get install calculix-ccx");
  }
  fs::create_directories(fea);
  fs::copy_file(inp, fea / "model.inp", fs::copy_options::overwrite_existing);
  fs::copy_file(plies_csv, fea / "model_plies.csv", fs::copy_options::overwrite_existing);
  fs::remove(fea / "model.dat");
  std::cerr << "windplan check-fea: ccx -i model in " << fea.string() << " ...\n";
  const std::string cmd = "cd " + quoted(fea) + " && ccx -i model > ccx.log 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream logf(fea / "ccx.log");
  std::stringstream log;
  log << logf.rdbuf();
  const std::size_t err = log.str().find("*ERROR");
  if (rc != 0 || err != std::string::npos || !fs::exists(fea / "model.dat")) {
    std::string line = err == std::string::npos ? "" : log.str().substr(err, 160);
    line = line.substr(0, line.find('\n'));
    throw InputError("ccx failed on " + (fea / "model.inp").string() + " (exit " +
                     std::to_string(rc) + ")" + (line.empty() ? "" : ": " + line) + "; see " +
                     (fea / "ccx.log").string());
  }
  // Layer names from the deck's comments ("** layer k: name").
  std::vector<std::string> names;
  {
    std::ifstream in(inp);
    std::string l;
    while (std::getline(in, l)) {
      if (l.rfind("** layer ", 0) == 0 && l.find(": ") != std::string::npos) {
        names.push_back(l.substr(l.find(": ") + 2));
      }
      if (l.rfind("*NODE", 0) == 0) break;
    }
  }
  const ElasticConstants ply = rule_of_mixtures(job.design.ply);
  const PlyAllowables al =
      ply_allowables(ply, job.design.allowable_stress(), job.design.transverse_strength,
                     job.design.shear_strength);
  const CcxResults res = read_ccx_dat(fea / "model.dat");
  const CsvTable plies = read_numeric_csv(plies_csv);
  // Away from the open ends: elements farther than 2 shell edges from a free edge.
  const double zone = 2.0 * job.design.fea_edge;
  const std::set<int> edges = elements_near_free_edges(read_inp_mesh(inp), zone);
  const FeaCheck check = check_plies(res, plies, names, al, edges);
  const FeaCheck whole = check_plies(res, plies, names, al);
  const double p = job.design.has_pressure() ? job.design.pressure : 1.0;

  CsvTable t;
  t.header = {"layer",
              "fibre_strain_max",
              "fibre_strain_min",
              "fibre_strain_mean",
              "fibre_stress_max [MPa]",
              "fibre_stress_min [MPa]",
              "failure_factor",
              "fibre_factor",
              "element"};
  std::ostringstream md;
  md << "# " << job.name << ": structural check (CalculiX)\n\n"
     << "Model " << inp.string() << " under " << format_number("%g", p) << " MPa, "
     << check.elements << " elements checked (" << edges.size()
     << " within 2 shell edges of the open ends left out). Criterion: maximum strain, allowables "
        "eps_1u "
     << format_number("%.5g", al.fibre_strain) << ", eps_2u "
     << format_number("%.5g", al.transverse_strain) << ", gamma_u "
     << format_number("%.5g", al.shear_strain)
     << " (export/files/ccx_results.h).\n\n| layer | fibre strain max / min / mean | fibre "
        "stress max / min [MPa] | failure factor (mode, element) | fibre factor |\n"
        "|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < check.layers.size(); ++k) {
    const FeaLayerCheck& L = check.layers[k];
    md << "| " << k + 1 << " " << L.name << " | " << format_number("%.5g", L.fibre_strain_max)
       << " / " << format_number("%.5g", L.fibre_strain_min) << " / "
       << format_number("%.5g", L.fibre_strain_mean) << " | "
       << format_number("%.5g", L.fibre_stress_max) << " / "
       << format_number("%.5g", L.fibre_stress_min) << " | "
       << format_number("%.4f", L.failure_factor) << " (" << L.mode << ", " << L.element << ") | "
       << format_number("%.4f", L.fibre_factor) << " |\n";
    t.rows.push_back({static_cast<double>(k), L.fibre_strain_max, L.fibre_strain_min,
                      L.fibre_strain_mean, L.fibre_stress_max, L.fibre_stress_min, L.failure_factor,
                      L.fibre_factor, static_cast<double>(L.element)});
  }
  std::ostringstream sum;
  sum << "first-ply failure factor " << format_number("%.4f", check.failure_factor) << " ("
      << check.governing << "; max-strain) at " << format_number("%g", p)
      << " MPa: first ply fails at " << format_number("%.4g", p / check.failure_factor)
      << " MPa; fibre factor " << format_number("%.4f", check.fibre_factor) << ": fibre failure at "
      << format_number("%.4g", p / check.fibre_factor) << " MPa";
  sum << "\n  (elements within " << format_number("%g", zone)
      << " mm of the model's open ends, where the bosses are not modelled, are left out: "
      << edges.size() << " elements; with them the factor is "
      << format_number("%.4f", whole.failure_factor) << ", " << whole.governing << ")";
  md << "\n" << sum.str() << ".\n";
  write_text_atomically(fea / "fea_check.md", md.str());
  write_csv_file(fea / "fea_layers.csv", t);
  std::cout << md.str().substr(md.str().find("| layer"));
  std::cout << "\n  " << sum.str() << "\n  files in " << fea.string()
            << ": fea_check.md fea_layers.csv model.dat ccx.log\n";
  return 0;
}

}  // namespace windplan::cli
