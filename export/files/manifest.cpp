#include "export/files/manifest.h"

#include <set>
#include <system_error>

#include "export/files/sha256.h"
#include "geometry/base/errors.h"

namespace windplan {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      static const char* digits = "0123456789abcdef";
      out += "\\u00";
      out += digits[u >> 4];
      out += digits[u & 15];
    } else {
      out += c;
    }
  }
  return out + "\"";
}

void entries(std::string* out, const char* key, const std::vector<ManifestEntry>& list,
             bool inputs) {
  *out += std::string("  \"") + key + "\": [";
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ManifestEntry& e = list[i];
    *out += i ? ",\n    " : "\n    ";
    *out += std::string("{\"") + (inputs ? "role" : "name") + "\": " + quoted(e.name);
    if (inputs) *out += ", \"path\": " + quoted(e.path);
    *out += ", \"size\": " + std::to_string(e.size) + ", \"sha256\": " + quoted(e.sha256) + "}";
  }
  *out += list.empty() ? "]" : "\n  ]";
}

}  // namespace

ManifestEntry manifest_entry(const std::filesystem::path& file, const std::string& name,
                             bool with_path) {
  ManifestEntry e;
  e.name = name;
  if (with_path) e.path = std::filesystem::absolute(file).lexically_normal().string();
  std::error_code ec;
  e.size = std::filesystem::file_size(file, ec);
  if (ec) throw IoError(file.string() + ": cannot read its size: " + ec.message());
  e.sha256 = sha256_file(file);
  return e;
}

std::string manifest_json(const Manifest& m) {
  std::string out = "{\n  \"windplan_manifest\": 1,\n";
  out += "  \"windplan_version\": " + quoted(m.version) + ",\n";
  out += "  \"job\": " + quoted(m.job) + ",\n";
  entries(&out, "inputs", m.inputs, true);
  out += ",\n";
  entries(&out, "files", m.files, false);
  out += "\n}\n";
  return out;
}

std::vector<std::string> manifest_file_names(const std::string& json) {
  std::vector<std::string> names;
  if (json.find("\"windplan_manifest\": 1") == std::string::npos) return names;
  std::size_t pos = json.find("\"files\": [");
  if (pos == std::string::npos) return names;
  const std::string key = "{\"name\": \"";
  while ((pos = json.find(key, pos)) != std::string::npos) {
    pos += key.size();
    std::string name;
    while (pos < json.size() && json[pos] != '"') {
      if (json[pos] == '\\' && pos + 1 < json.size()) ++pos;
      name += json[pos++];
    }
    names.push_back(name);
  }
  return names;
}

namespace {

// A cursor over the manifest text for parse_manifest_files.
struct Cursor {
  const std::string& s;
  std::size_t i = 0;
  bool eat(const std::string& lit) {
    if (s.compare(i, lit.size(), lit) != 0) return false;
    i += lit.size();
    return true;
  }
  void space() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\n')) ++i;
  }
  // A string as quoted() writes it: \" \\ and \u00XX escapes only.
  bool string(std::string* out) {
    if (!eat("\"")) return false;
    out->clear();
    while (i < s.size() && s[i] != '"') {
      char c = s[i++];
      if (c == '\\') {
        if (i >= s.size()) return false;
        c = s[i++];
        if (c == 'u') {
          if (i + 4 > s.size() || s.compare(i, 2, "00") != 0) return false;
          const std::string hex = s.substr(i + 2, 2);
          i += 4;
          if (hex.find_first_not_of("0123456789abcdef") != std::string::npos) return false;
          c = static_cast<char>(std::stoi(hex, nullptr, 16));
        } else if (c != '"' && c != '\\') {
          return false;
        }
      }
      *out += c;
    }
    return eat("\"");
  }
  bool number(std::uintmax_t* out) {
    const std::size_t start = i;
    *out = 0;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9' && i - start < 19) {
      *out = *out * 10 + static_cast<std::uintmax_t>(s[i++] - '0');
    }
    return i > start && (i >= s.size() || s[i] < '0' || s[i] > '9');
  }
};

}  // namespace

bool parse_manifest_files(const std::string& json, std::vector<ManifestEntry>* files) {
  files->clear();
  if (json.compare(0, 27, "{\n  \"windplan_manifest\": 1,") != 0) return false;
  const std::size_t at = json.find("\n  \"files\": [");
  if (at == std::string::npos) return false;
  Cursor c{json, at + 13};
  std::set<std::string> seen;
  std::vector<ManifestEntry> out;
  c.space();
  if (!c.eat("]")) {
    for (;;) {
      c.space();
      ManifestEntry e;
      if (!c.eat("{\"name\": ") || !c.string(&e.name) || !c.eat(", \"size\": ") ||
          !c.number(&e.size) || !c.eat(", \"sha256\": ") || !c.string(&e.sha256) || !c.eat("}")) {
        return false;
      }
      if (e.name.empty() || e.name == "." || e.name == ".." || e.name == "manifest.json" ||
          e.name.find_first_of(std::string("/\0", 2)) != std::string::npos ||
          e.sha256.size() != 64 ||
          e.sha256.find_first_not_of("0123456789abcdef") != std::string::npos ||
          !seen.insert(e.name).second) {
        return false;
      }
      out.push_back(e);
      c.space();
      if (c.eat("]")) break;
      if (!c.eat(",")) return false;
    }
  }
  c.space();
  if (!c.eat("}") || (c.i < json.size() && !(c.eat("\n") && c.i == json.size()))) return false;
  *files = std::move(out);
  return true;
}

}  // namespace windplan
