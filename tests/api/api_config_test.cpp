// The `api:` section: defaults, every key, and an error naming the key for each bad value.
#include "daemon/api/api_config.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace fibrecell;
using namespace fibrecell::api;

namespace {

ApiConfig load(const std::string& yaml) {
    auto root = config::Section::load_text(yaml, "cell.yaml");
    return load_api_config(root.section("api"));
}

// The ConfigError message of loading `yaml`; "" when it loads.
std::string error_of(const std::string& yaml) {
    try {
        load(yaml);
    } catch (const config::ConfigError& e) {
        return e.what();
    }
    return "";
}

const std::string kConfigToken = "0123456789abcdef0123";

}  // namespace

TEST(ApiConfig, DefaultsWhenTheSectionIsAbsent) {
    const ApiConfig c = load("name: cell-1\n");
    EXPECT_EQ(c.socket_path, "/run/fibrecelld/api.sock");
    EXPECT_EQ(c.socket_mode, 0660u);
    EXPECT_EQ(c.socket_group, "");
    EXPECT_FALSE(c.tcp.enabled);
    EXPECT_EQ(c.tcp.host, "127.0.0.1");
    EXPECT_EQ(c.tcp.port, 7420);
    EXPECT_EQ(c.max_request_bytes, 16u << 20);
    EXPECT_EQ(c.max_clients, 64);
    EXPECT_DOUBLE_EQ(c.progress_rate_hz, 2.0);
}

TEST(ApiConfig, ReadsEveryKey) {
    const ApiConfig c = load(
        "api:\n"
        "  socket: /tmp/fc/api.sock\n"
        "  socket_mode: \"0640\"\n"
        "  socket_group: \"65534\"\n"
        "  max_request_bytes: 4096\n"
        "  max_clients: 3\n"
        "  progress_rate_hz: 5\n"
        "  max_client_queue_bytes: 131072\n"
        "  tcp:\n"
        "    enabled: true\n"
        "    host: 0.0.0.0\n"
        "    port: 7500\n"
        "    token: " +
        kConfigToken +
        "\n"
        "    auth_timeout_ms: 500\n");
    EXPECT_EQ(c.socket_path, "/tmp/fc/api.sock");
    EXPECT_EQ(c.socket_mode, 0640u);
    EXPECT_EQ(c.socket_group, "65534");
    EXPECT_EQ(c.max_request_bytes, 4096u);
    EXPECT_EQ(c.max_clients, 3);
    EXPECT_DOUBLE_EQ(c.progress_rate_hz, 5.0);
    EXPECT_EQ(c.max_client_queue_bytes, 131072u);
    EXPECT_TRUE(c.tcp.enabled);
    EXPECT_EQ(c.tcp.host, "0.0.0.0");
    EXPECT_EQ(c.tcp.port, 7500);
    EXPECT_EQ(c.tcp.token, kConfigToken);
    EXPECT_EQ(c.tcp.auth_timeout.count(), 500);
}

TEST(ApiConfig, SocketModeIsOctalInEveryUsualSpelling) {
    EXPECT_EQ(load("api: {socket_mode: \"0660\"}\n").socket_mode, 0660u);
    EXPECT_EQ(load("api: {socket_mode: 0600}\n").socket_mode, 0600u);  // unquoted YAML
    EXPECT_EQ(load("api: {socket_mode: 640}\n").socket_mode, 0640u);
    EXPECT_EQ(load("api: {socket_mode: 0o666}\n").socket_mode, 0666u);
    for (const char* bad : {"\"0999\"", "rw-rw----", "\"01777\"", "[6, 6, 0]"}) {
        const std::string e = error_of(std::string("api:\n  socket_mode: ") + bad + "\n");
        EXPECT_NE(e.find("cell.yaml: line 2: api.socket_mode: must be an octal file mode"),
                  std::string::npos)
            << bad << " -> " << e;
    }
}

TEST(ApiConfig, SocketPathMustBeAbsoluteAndFitSunPath) {
    EXPECT_NE(
        error_of("api: {socket: run/api.sock}\n").find("api.socket: must be an absolute path"),
        std::string::npos);
    const std::string e = error_of("api: {socket: /" + std::string(120, 'a') + "}\n");
    EXPECT_NE(e.find("api.socket: is 121 bytes long; a Unix socket path may have at most 107"),
              std::string::npos)
        << e;
}

TEST(ApiConfig, UnknownKeysAreRejectedWithTheirPath) {
    EXPECT_NE(error_of("api:\n  sockett: /x\n").find("cell.yaml: line 2: api.sockett: unknown key"),
              std::string::npos);
    EXPECT_NE(error_of("api:\n  tcp:\n    prot: 1\n").find("api.tcp.prot: unknown key"),
              std::string::npos);
}

TEST(ApiConfig, TcpNeedsAToken) {
    const std::string e = error_of("api:\n  tcp:\n    enabled: true\n");
    EXPECT_NE(e.find("api.tcp.enabled: TCP needs a token: set tcp.token or tcp.token_file"),
              std::string::npos)
        << e;
    EXPECT_NE(error_of("api: {tcp: {token: short}}\n").find("api.tcp.token: must be at least 16"),
              std::string::npos);
    const std::string both =
        error_of("api: {tcp: {token: " + kConfigToken + ", token_file: /etc/token}}\n");
    EXPECT_NE(both.find("api.tcp.token_file: give token or token_file, not both"),
              std::string::npos)
        << both;
}

TEST(ApiConfig, TokenFileIsReadAndTrimmed) {
    const fibrecell::test::TempDir dir("api-token");
    const auto path = dir.write("token", std::string("  ") + kConfigToken + "  \n# comment line\n");
    const ApiConfig c = load("api: {tcp: {enabled: true, token_file: " + path.string() + "}}\n");
    EXPECT_EQ(c.tcp.token, kConfigToken);
    std::filesystem::remove(path);
    const std::string e = error_of("api: {tcp: {token_file: " + path.string() + "}}\n");
    EXPECT_NE(
        e.find("api.tcp.token_file: cannot read " + path.string() + ": No such file or directory"),
        std::string::npos)
        << e;
}

TEST(ApiConfig, GroupMustExist) {
    const std::string e = error_of("api: {socket_group: no-such-group-xyz}\n");
    EXPECT_NE(e.find("api.socket_group: no group 'no-such-group-xyz' on this system"),
              std::string::npos)
        << e;
    EXPECT_EQ(load("api: {socket_group: root}\n").socket_group, "root");
}

TEST(ApiConfig, HostPortAndLimitsAreChecked) {
    EXPECT_NE(error_of("api: {tcp: {host: localhost}}\n")
                  .find("api.tcp.host: must be an IP address (127.0.0.1, ::1, 0.0.0.0), got "
                        "'localhost'"),
              std::string::npos);
    EXPECT_NE(error_of("api: {tcp: {port: 70000}}\n").find("api.tcp.port: must be in [0, 65535]"),
              std::string::npos);
    EXPECT_NE(error_of("api: {max_request_bytes: 10}\n")
                  .find("api.max_request_bytes: must be in [1024, 1073741824], got 10"),
              std::string::npos);
    EXPECT_NE(error_of("api: {progress_rate_hz: 0}\n").find("api.progress_rate_hz: must be in (0"),
              std::string::npos);
    EXPECT_NE(error_of("api: {max_clients: 0}\n").find("api.max_clients: must be in [1, 10000]"),
              std::string::npos);
    EXPECT_NE(
        error_of("api: {tcp: {enabled: maybe}}\n").find("api.tcp.enabled: must be true or false"),
        std::string::npos);
}

TEST(ApiConfig, BareNodeNamesTheOriginAndKey) {
    const YAML::Node node = YAML::Load("socket: /x.sock\nmax_clients: -1\n");
    try {
        load_api_config(node, "fibrecelld.yaml");
        FAIL() << "accepted max_clients -1";
    } catch (const config::ConfigError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "fibrecelld.yaml: line 2: api.max_clients: must be in [1, 10000], got -1");
    }
    EXPECT_EQ(load_api_config(YAML::Load("socket: /x.sock"), "f").socket_path, "/x.sock");
}

TEST(ApiConfig, OctalModeParser) {
    unsigned mode = 0;
    EXPECT_TRUE(parse_octal_mode("0777", mode));
    EXPECT_EQ(mode, 0777u);
    EXPECT_TRUE(parse_octal_mode("0", mode));
    EXPECT_EQ(mode, 0u);
    EXPECT_FALSE(parse_octal_mode("", mode));
    EXPECT_FALSE(parse_octal_mode("0o", mode));
    EXPECT_FALSE(parse_octal_mode("1000", mode));
    EXPECT_FALSE(parse_octal_mode("0x1ff", mode));
}

TEST(ApiConfig, TheDashboardsHttpSection) {
    const ApiConfig off = load("name: cell-1\n");
    EXPECT_FALSE(off.http.enabled);
    EXPECT_EQ(off.http.host, "127.0.0.1");
    EXPECT_EQ(off.http.port, 7480);
    EXPECT_EQ(off.http.web_root, "");

    const ApiConfig c = load("api:\n  http:\n    enabled: true\n    port: 0\n    token: " + kConfigToken +
                             "\n    session_hours: 2\n    login_failures_per_minute: 9\n"
                             "    secure_cookie: true\n    web_root: /srv/fibrecell-web\n");
    EXPECT_TRUE(c.http.enabled);
    EXPECT_EQ(c.http.port, 0);
    EXPECT_EQ(c.http.token, kConfigToken);
    EXPECT_EQ(c.http.session_lifetime, std::chrono::hours(2));
    EXPECT_EQ(c.http.login_failures_per_minute, 9);
    EXPECT_TRUE(c.http.secure_cookie);
    EXPECT_EQ(c.http.web_root, "/srv/fibrecell-web");

    test::TempDir dir("api-http-token");
    std::ofstream(dir / "dashboard.token") << "  " << kConfigToken << "  \nsecond line\n";
    EXPECT_EQ(load("api:\n  http: {token_file: " + (dir / "dashboard.token").string() + "}\n").http.token,
              kConfigToken);
    EXPECT_EQ(read_token_file((dir / "dashboard.token").string()), kConfigToken);

    EXPECT_NE(error_of("api:\n  http: {enabled: true}\n").find("api.http.enabled: the dashboard needs a token"),
              std::string::npos);
    EXPECT_NE(error_of("api:\n  http: {token: short}\n").find("api.http.token"), std::string::npos);
    EXPECT_NE(error_of("api:\n  http: {host: dashboard.local}\n").find("api.http.host"), std::string::npos);
    EXPECT_NE(error_of("api:\n  http: {session_hours: 0}\n").find("api.http.session_hours"), std::string::npos);
    EXPECT_NE(error_of("api:\n  http: {web_root: relative/dir}\n").find("api.http.web_root"), std::string::npos);
    EXPECT_NE(error_of("api:\n  http: {tls: true}\n").find("api.http.tls"), std::string::npos);
    EXPECT_THROW(read_token_file((dir / "missing").string()), std::runtime_error);
}
