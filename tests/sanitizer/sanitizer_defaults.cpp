// Linked into every executable of the sanitizer build (WINDPLAN_SANITIZE=ON): the default
// options of the sanitizers, so that ctest, gtest discovery and the CLI run as a subprocess all
// use the same settings without environment variables. LeakSanitizer reads the named suppression
// file, tests/sanitizer/lsan_occt.supp (OpenCASCADE's one-time static setup; explained there).
// Variables ASAN_OPTIONS / UBSAN_OPTIONS / LSAN_OPTIONS set by the user still take precedence.
extern "C" {

const char* __asan_default_options() { return "detect_leaks=1:abort_on_error=0"; }

const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }

const char* __lsan_default_options() {
  return "suppressions=" WINDPLAN_LSAN_SUPPRESSIONS ":print_suppressions=0";
}

}  // extern "C"
