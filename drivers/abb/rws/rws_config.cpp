#include "drivers/abb/rws/rws_config.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>

namespace fibrecell::drivers::abb::rws {

namespace {

// HOME:-relative, '/'-separated, no empty or ".." parts: FcMain's 60-character limit on
// sFcJobDir leaves 54 for the folder after "HOME:/".
bool valid_job_dir(const std::string& dir) {
    if (dir.empty() || dir.size() > 54 || dir.front() == '/' || dir.back() == '/') return false;
    std::size_t start = 0;
    while (start <= dir.size()) {
        const std::size_t end = std::min(dir.find('/', start), dir.size());
        const std::string part = dir.substr(start, end - start);
        if (part.empty() || part == "." || part == "..") return false;
        for (char ch : part)
            if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
                return false;
        start = end + 1;
    }
    return true;
}

}  // namespace

RwsLinkConfig load_rws_config(config::Section s) {
    using std::chrono::milliseconds;
    RwsLinkConfig c;
    c.client.host = s.get_or<std::string>("host", c.client.host);
    c.client.port = static_cast<std::uint16_t>(s.integer("port", c.client.port, 1, 65535));
    c.client.user = s.get_or<std::string>("user", c.client.user);
    c.client.password = s.get_or<std::string>("password", c.client.password);
    c.client.task = s.get_or<std::string>("task", c.client.task);
    c.client.connect_timeout = milliseconds(s.integer("connect_timeout_ms", 2000, 1, 60000));
    c.client.request_timeout = milliseconds(s.integer("request_timeout_ms", 5000, 1, 600000));
    c.job_dir = s.get_or<std::string>("job_dir", c.job_dir);
    if (!valid_job_dir(c.job_dir))
        s.fail("job_dir",
               "must be a folder under HOME: of at most 54 characters: letters, digits, _ and -, "
               "parts separated by '/', no '..'");
    s.finish();
    return c;
}

}  // namespace fibrecell::drivers::abb::rws
