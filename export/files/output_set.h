#pragma once
// An output folder that always holds one job's complete set of files, or the previous one, never
// a mix (a Marlin run's toolpath.gcode beside a later pipe run's toolpath.ngc, half-written CSVs,
// another job's report.json).
//
//   OutputSet set(dir);               // lock, checks, fresh staging folder beside dir
//   export_plan(..., set.staging());  // write every file there
//   set.commit(manifest);             // manifest.json, fsync, swap the staging folder in whole
//
// - --out is checked before anything is created: a symbolic link (dangling or not), a mount
//   point or a file is refused at once (a rename cannot swap them).
// - Lock: "<parent>/.<name>.lock" (flock, held from the constructor to the destructor, released
//   by the kernel however the process ends): a second run into the same folder is refused at
//   once, naming the holder's pid. The holder removes the lock file while holding it (on
//   return, exception, refusal or a catchable signal); a run that opened the file meanwhile
//   sees that its path no longer names it and opens it again. Only a SIGKILL leaves it.
// - Staging: "<parent>/.<name>.staging.<pid>", on the same file system as dir so that the swap
//   is a rename. commit() writes manifest.json last, fsyncs every file and the folder, then
//   exchanges staging and dir atomically (renameat2 RENAME_EXCHANGE; where the file system
//   cannot, two renames with dir briefly absent, never mixed), fsyncs the parent and removes the
//   previous set. No file of the previous set is kept: the folder is exactly the new set.
// - Only folders windplan wrote are replaced (verify_output_folder): dir must be absent, empty,
//   or a set whose manifest.json verifies. Anything else is refused, listing the foreign files:
//   a user's `--out .` or `--out ~/Documents` is never emptied, nor a folder holding only a
//   user's report.md (there is no rule for sets from before manifests), nor a file a forged
//   manifest lists. The folder is verified again just before the swap, and only the verified
//   files of the previous set are removed.
// - Clean-up: the destructor (normal return, exceptions) and SIGINT/SIGTERM/SIGHUP/SIGQUIT
//   handlers remove the staging folder and the lock file; a SIGKILL cannot be caught, and the
//   next run into the folder (holding the lock, so no other run owns them) removes windplan's
//   files from leftover staging folders, and the folders once empty.
#include <filesystem>
#include <string>
#include <vector>

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
  void release_lock();

  std::filesystem::path dir_;
  std::filesystem::path staging_;
  std::filesystem::path lock_path_;
  std::vector<std::string> previous_;  // the verified files of the set replaced by commit()
  int lock_fd_ = -1;
  bool committed_ = false;
};

/// Checks that an existing folder is a set windplan wrote, unchanged: a regular manifest.json
/// (at most 1 MiB) in windplan's layout, and every other entry a regular file it lists, with a
/// name windplan writes (is_windplan_output_name), its size and its SHA-256; every listed file
/// present. An empty folder passes. Returns the names to remove with it (manifest.json last).
/// \throw IoError listing the foreign files (at most 8 named, then a count) and why.
std::vector<std::string> verify_output_folder(const std::filesystem::path& dir);

/// The names windplan writes into an output folder, and "<name>.tmp.<digits>" temporaries of
/// them. A writer of a new file name adds it here, or a second run into its folder is refused.
bool is_windplan_output_name(const std::string& name);

/// Test hook: when the environment variable WINDPLAN_TEST_PAUSE_AFTER equals `name`, prints
/// "windplan: test pause after <name>" to stderr and sleeps until a signal ends the process,
/// so that a test can kill a run at a point it chooses. Does nothing otherwise.
void output_test_pause(const std::string& name);

}  // namespace windplan
