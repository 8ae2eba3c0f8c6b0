#pragma once
// Names a user gives (a job's name, which becomes a folder and lands in report.json, report.md
// and manifest.json) as text every reader shows the same way (issue 28: a name with byte 0xFF
// made report.json and manifest.json invalid UTF-8; a bidi override or a name of non-breaking
// spaces was accepted).
//
// check_name_text refuses, with the reason: bytes that are not UTF-8 (bad sequences, overlong
// forms, surrogates, beyond U+10FFFF), control characters (C0, DEL, C1), invisible format
// characters (bidi embeddings, overrides and isolates U+202A-U+202E, U+2066-U+2069, marks
// U+200E/U+200F/U+061C, zero-width U+200B-U+200D, U+2060-U+2064, U+FEFF, soft hyphen U+00AD),
// and a name that is blank (only spaces of any kind: U+0020, U+00A0, U+1680, U+2000-U+200A,
// U+202F, U+205F, U+3000).
#include <string>

namespace windplan {

/// True when `name` is shown as written; else false with the reason in *why (e.g. "is not
/// valid UTF-8 (byte 0xFF at byte 3)", "contains an invisible format character U+202E").
bool check_name_text(const std::string& name, std::string* why);

}  // namespace windplan
