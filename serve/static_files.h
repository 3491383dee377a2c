// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The files `lmk serve` sends besides the API: the page (serve/web/, compiled in) and three.js,
// read from its installed directory with every path confined to it.
#include <filesystem>
#include <string>
#include <vector>

namespace lmk::serve {

struct WebAsset {
  const char* name;  ///< "index.html", "app.js", ...
  const char* text;
};

/// The page's files, compiled in by serve/embed_web.cmake.
const std::vector<WebAsset>& web_assets();

struct StaticFile {
  std::string body;
  std::string content_type;
};

/// The MIME type for a file name's extension (JavaScript modules must be served as such).
std::string content_type_for(const std::string& name);

/// The page's file `name`; ApiError 404 for no such file.
StaticFile web_asset(const std::string& name);

/// Whether `path`, its links resolved, is `root` or lies inside it: the one test of confinement
/// for served files and for the landmark files programs name.
bool lies_within(const std::filesystem::path& path, const std::filesystem::path& root);

/// The file `relative` (a URL path, already decoded) under `root`. ApiError 403 for any path that
/// could leave `root` (a ".." segment, an absolute path, a backslash, a NUL) or that resolves
/// outside it through a link, and 404 for a missing file.
StaticFile confined_file(const std::filesystem::path& root, const std::string& relative);

}  // namespace lmk::serve
