#pragma once
// The dashboard's pages as files under one folder (docs/dashboard.md). Only plain files below the
// root are served, by a request path made of ordinary names: no "..", no hidden files, no
// directory listings, no symlink out of the root.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::http {

struct StaticFile {
    std::filesystem::path path;
    std::string content_type;
};

// The file for a request target ("/", "/app.js", "/vendor/uPlot.min.css?v=1"), or nullopt.
std::optional<StaticFile> find_static_file(const std::filesystem::path& root,
                                           std::string_view target);

// The pages' folder: `configured` when set, else the installed dashboard, else the build tree's.
std::filesystem::path default_web_root(const std::string& configured);

}  // namespace fibrecell::http
