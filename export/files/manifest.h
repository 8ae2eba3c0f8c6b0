#pragma once
// manifest.json: what an output folder holds, so that a shop can check a set before loading a
// program (`sha256sum` of each file against the manifest), and so that windplan knows which
// files of a folder it wrote (export/files/output_set.h replaces only such folders).
//
//   {
//     "windplan_manifest": 1,
//     "windplan_version": "0.1.0",
//     "job": "pipe",
//     "inputs": [ {"role": "job", "path": "/abs/pipe.yaml", "size": 412, "sha256": "..."}, ... ],
//     "files": [ {"name": "fibre_path.csv", "size": 1234, "sha256": "..."}, ... ]
//   }
//
// Inputs: the job file, the mandrel's mesh or CAD file, cut-line initial CSVs (absolute paths,
// hashed when read). Files: every file of the set except manifest.json itself, in the order
// written. No timestamps: two runs of one job give byte-identical manifests.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace windplan {

struct ManifestEntry {
  std::string name;         ///< file name in the set, or the input's role ("job", "mandrel", ...)
  std::string path;         ///< inputs: the absolute path; empty for files of the set
  std::uintmax_t size = 0;  ///< bytes
  std::string sha256;       ///< hex
};

struct Manifest {
  std::string job;
  std::string version;
  std::vector<ManifestEntry> inputs;
  std::vector<ManifestEntry> files;
};

/// An entry for a file on disk (size and hash read now). \throw IoError if it cannot be read.
ManifestEntry manifest_entry(const std::filesystem::path& file, const std::string& name,
                             bool with_path);

/// The JSON text (fixed layout, one entry per line).
std::string manifest_json(const Manifest& m);

/// The "name" of every entry of "files" in a manifest's text; empty when the text is not a
/// windplan manifest. (A reader for the layout above, not a general JSON parser.)
std::vector<std::string> manifest_file_names(const std::string& json);

/// The "files" entries of a manifest's text (name, size, sha256), read strictly in the layout
/// manifest_json writes: false (and `files` cleared) when the text is anything else (another
/// layout, a name given twice, a name with '/' or NUL, a hash that is not 64 hex digits). Used
/// to verify an output folder before it is replaced (export/files/output_set.h).
bool parse_manifest_files(const std::string& json, std::vector<ManifestEntry>* files);

}  // namespace windplan
