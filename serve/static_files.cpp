// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/static_files.h"

#include <fstream>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {

namespace fs = std::filesystem;

std::string content_type_for(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  // Not text/javascript: httplib compresses every text/ type with brotli, 2 s for three.js.
  if (ext == ".js" || ext == ".mjs") return "application/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  return "application/octet-stream";
}

StaticFile web_asset(const std::string& name) {
  if (name.find('/') != std::string::npos || name.find("..") != std::string::npos) {
    throw forbidden("'" + printable(name, kEchoedBytes) + "' is outside the served files");
  }
  for (const WebAsset& a : web_assets()) {
    if (name == a.name) return {a.text, content_type_for(name)};
  }
  throw not_found("no page file '" + printable(name, kEchoedBytes) + "'");
}

bool lies_within(const fs::path& path, const fs::path& root) {
  const fs::path p = fs::weakly_canonical(path);
  const fs::path r = fs::weakly_canonical(root);
  auto pi = p.begin();
  for (auto ri = r.begin(); ri != r.end(); ++ri, ++pi) {
    if (pi == p.end() || *pi != *ri) return false;
  }
  return true;
}

StaticFile confined_file(const fs::path& root, const std::string& relative) {
  // Refused on the path's text alone, before the file system is asked anything.
  const fs::path rel(relative);
  const bool escapes = relative.empty() || rel.is_absolute() ||
                       relative.find('\\') != std::string::npos ||
                       relative.find('\0') != std::string::npos;
  bool dot_segment = false;
  for (const fs::path& part : rel) {
    if (part == ".." || part == ".") dot_segment = true;
  }
  if (escapes || dot_segment)
    throw forbidden("'" + printable(relative, kEchoedBytes) + "' is outside the served files");
  // And once resolved: a link inside root must not lead out of it.
  if (!fs::is_directory(root)) throw not_found("three.js is not installed at " + root.string());
  const fs::path file = root / rel;
  if (!fs::is_regular_file(file))
    throw not_found("no file '" + printable(relative, kEchoedBytes) + "'");
  if (!lies_within(file, root))
    throw forbidden("'" + printable(relative, kEchoedBytes) + "' is outside the served files");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream body;
  body << in.rdbuf();
  return {body.str(), content_type_for(file.string())};
}

}  // namespace lmk::serve
