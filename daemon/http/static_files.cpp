#include "daemon/http/static_files.hpp"

#include <array>
#include <utility>

namespace fibrecell::http {

namespace fs = std::filesystem;

namespace {

std::string content_type_of(const fs::path& p) {
    static constexpr std::array<std::pair<std::string_view, std::string_view>, 10> types{{
        {".html", "text/html; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".mjs", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".svg", "image/svg+xml"},
        {".png", "image/png"},
        {".json", "application/json"},
        {".ico", "image/x-icon"},
        {".woff2", "font/woff2"},
        {".txt", "text/plain; charset=utf-8"},
    }};
    const std::string ext = p.extension().string();
    for (const auto& [e, type] : types)
        if (ext == e) return std::string(type);
    return "application/octet-stream";
}

// Each segment an ordinary name: letters, digits, '-', '_', '.', not starting with '.'.
bool ordinary_path(std::string_view path) {
    if (path.empty()) return false;
    std::size_t start = 0;
    while (start <= path.size()) {
        const auto end = std::min(path.find('/', start), path.size());
        const std::string_view segment = path.substr(start, end - start);
        if (segment.empty() || segment.front() == '.') return false;
        for (const char c : segment) {
            const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                            (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
            if (!ok) return false;
        }
        start = end + 1;
    }
    return true;
}

}  // namespace

std::optional<StaticFile> find_static_file(const fs::path& root, std::string_view target) {
    target = target.substr(0, target.find_first_of("?#"));
    if (target.empty() || target.front() != '/') return std::nullopt;
    std::string_view relative = target.substr(1);
    if (relative.empty() || relative.back() == '/') return std::nullopt;  // "/" is handled by the caller
    if (!ordinary_path(relative)) return std::nullopt;
    std::error_code ec;
    const fs::path base = fs::canonical(root, ec);
    if (ec) return std::nullopt;
    const fs::path file = fs::canonical(base / fs::path(relative), ec);
    if (ec || !fs::is_regular_file(file, ec)) return std::nullopt;
    // A symlink inside the root may not lead out of it.
    const auto [b, f] = std::mismatch(base.begin(), base.end(), file.begin(), file.end());
    if (b != base.end()) return std::nullopt;
    return StaticFile{file, content_type_of(file)};
}

fs::path default_web_root(const std::string& configured) {
    if (!configured.empty()) return configured;
    std::error_code ec;
    if (fs::is_directory(FIBRECELL_INSTALLED_WEB_DIR, ec)) return FIBRECELL_INSTALLED_WEB_DIR;
    return FIBRECELL_BUILD_WEB_DIR;
}

}  // namespace fibrecell::http
