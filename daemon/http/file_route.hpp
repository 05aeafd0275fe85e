#pragma once
// A route to files behind the dashboard's login (HttpServer::add_file_route), in a header of its
// own so that a component can offer one without Asio's headers.

#include <filesystem>
#include <functional>
#include <optional>
#include <string_view>

namespace fibrecell::http {

// Files behind the login: a request for PREFIX KEY/PATH is the file PATH below the folder the
// resolver gives for KEY (nullopt: not found), served like a page: ordinary names only, nothing
// outside that folder. It runs on an io thread.
using FileResolver = std::function<std::optional<std::filesystem::path>(std::string_view key)>;

}  // namespace fibrecell::http
