#pragma once
// An output folder that always holds one job's complete set of files, or the previous one, never
// a mix (a Marlin run's toolpath.gcode beside a later pipe run's toolpath.ngc, half-written CSVs,
// another job's report.json).
//
//   OutputSet set(dir);               // lock, checks, fresh staging folder beside dir
//   export_plan(..., set.staging());  // write every file there
//   set.commit(manifest);             // manifest.json, fsync, swap the staging folder in whole
//
// - Lock: "<parent>/.<name>.lock" (flock, held from the constructor to the destructor, released
//   by the kernel however the process ends): a second run into the same folder is refused at
//   once, naming the holder's pid. The empty lock file stays (removing it would race).
// - Staging: "<parent>/.<name>.staging.<pid>", on the same file system as dir so that the swap
//   is a rename. commit() writes manifest.json last, fsyncs every file and the folder, then
//   exchanges staging and dir atomically (renameat2 RENAME_EXCHANGE; where the file system
//   cannot, two renames with dir briefly absent, never mixed), fsyncs the parent and removes the
//   previous set. No file of the previous set is kept: the folder is exactly the new set.
// - Only folders windplan wrote are replaced: dir must be absent, empty, a set with a
//   manifest.json naming every file in it, or (sets from before manifests) hold only windplan's
//   output names. Anything else is refused, naming a foreign file: a user's `--out .` or
//   `--out ~/Documents` is never emptied.
// - Clean-up: the destructor (normal return, exceptions) and SIGINT/SIGTERM/SIGHUP/SIGQUIT
//   handlers remove the staging folder; a SIGKILL cannot be caught, and the next run into the
//   folder (holding the lock, so no other run owns them) removes leftover staging folders.
#include <filesystem>
#include <string>

#include "export/files/manifest.h"

namespace windplan {

class OutputSet {
 public:
  /// \throw IoError when dir cannot be used (locked by another run, not a windplan folder,
  ///        a file, not writable), naming it.
  explicit OutputSet(const std::filesystem::path& dir);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  const std::filesystem::path& directory() const { return dir_; }
  const std::filesystem::path& staging() const { return staging_; }

  /// Adds manifest.json (m.files gets every file of the staging folder, in the order given by
  /// `order`, then any others by name) and swaps the set in. \throw IoError.
  void commit(Manifest m, const std::vector<std::string>& order);

 private:
  std::filesystem::path dir_;
  std::filesystem::path staging_;
  int lock_fd_ = -1;
  bool committed_ = false;
};

/// The names windplan writes into an output folder (for folders from before manifests).
bool is_windplan_output_name(const std::string& name);

/// Test hook: when the environment variable WINDPLAN_TEST_PAUSE_AFTER equals `name`, prints
/// "windplan: test pause after <name>" to stderr and sleeps until a signal ends the process,
/// so that a test can kill a run at a point it chooses. Does nothing otherwise.
void output_test_pause(const std::string& name);

}  // namespace windplan
