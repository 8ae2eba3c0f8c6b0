#include "export/files/manifest.h"

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

}  // namespace windplan
