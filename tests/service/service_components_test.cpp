// The service as components (daemon/component/component.hpp): every method and event on the one
// registry has an owner and is listed with it in docs/socket-api.md, and the printer's start gate
// holds a start whichever way it comes. The service runs in this process here (the other service
// tests run fibrecelld), so that the test can register a gate of its own.
#include "service_fixture.hpp"

#include "daemon/api/api_error.hpp"
#include "daemon/printer/printer_component.hpp"
#include "daemon/service/service.hpp"

#include <boost/asio/io_context.hpp>

#include <atomic>
#include <regex>
#include <set>
#include <thread>

namespace fibrecell::test {
namespace service_components_test {

using daemon::service::Service;

// docs/socket-api.md's "Methods and events" table: name -> "owner" or "owner, control".
std::map<std::string, std::string> documented_endpoints() {
    std::istringstream doc(read_file(source_path("docs/socket-api.md")));
    std::map<std::string, std::string> out;
    bool in_table = false;
    const std::regex row(R"(^\| `([a-z_.]+)` \| ([a-z]+(?:, [a-z]+)*) \| (control)? *\|)");
    for (std::string line; std::getline(doc, line);) {
        if (line.rfind("## ", 0) == 0) in_table = line == "## Methods and events";
        std::smatch m;
        if (in_table && std::regex_search(line, m, row))
            out[m[1]] = m[2].str() + (m[3].matched ? ", control" : "");
    }
    return out;
}

// The registry as the same map; events of several owners as "a, b" in name order.
std::map<std::string, std::string> registered_endpoints(const api::ApiServer& api) {
    std::map<std::string, std::string> out;
    for (const auto& m : api.methods()) {
        EXPECT_FALSE(m.owner.empty()) << m.name << " has no owner";
        out[m.name] = m.owner + (m.control ? ", control" : "");
    }
    for (const auto& e : api.events()) {
        EXPECT_FALSE(e.owner.empty()) << e.name << " has no owner";
        std::string& owners = out[e.name];
        owners += (owners.empty() ? "" : ", ") + e.owner;
    }
    return out;
}

TEST_F(ServiceTest, EveryEndpointHasAnOwnerAndTheDocsListItWithThatOwner) {
    boost::asio::io_context io;
    Service service(io, daemon::service::load_service_config(write_config().string()));
    const auto registered = registered_endpoints(service.api());
    const auto documented = documented_endpoints();
    ASSERT_GE(documented.size(), 15u) << "docs/socket-api.md: no \"Methods and events\" table read";
    for (const auto& [name, owner] : registered)
        EXPECT_EQ(documented.contains(name) ? documented.at(name) : "(not in docs/socket-api.md)", owner)
            << name;
    for (const auto& [name, owner] : documented)
        EXPECT_TRUE(registered.contains(name)) << name << " is documented but nobody registers it";
}

// docs/layout.md's component map: component -> (folder, the endpoints its row names).
struct MapRow {
    std::string folder;
    std::set<std::string> endpoints;
};
std::map<std::string, MapRow> component_map() {
    std::istringstream doc(read_file(source_path("docs/layout.md")));
    std::map<std::string, MapRow> out;
    bool in_section = false;
    const std::regex row(R"(^\| ([a-z]+) \| `([a-z/]+)` \|(?:[^|]*\|){2}([^|]*)\|)");
    const std::regex name("`([a-z_.]+)`");
    for (std::string line; std::getline(doc, line);) {
        if (line.rfind("## ", 0) == 0) in_section = line == "## Components";
        std::smatch m;
        if (!in_section || !std::regex_search(line, m, row)) continue;
        MapRow& r = out[m[1]];
        r.folder = m[2];
        const std::string cell = m[3];
        for (std::sregex_iterator it(cell.begin(), cell.end(), name), end; it != end; ++it)
            r.endpoints.insert((*it)[1]);
    }
    return out;
}

TEST_F(ServiceTest, TheComponentMapListsEveryOwnerWithItsEndpoints) {
    boost::asio::io_context io;
    Service service(io, daemon::service::load_service_config(write_config().string()));
    std::map<std::string, std::set<std::string>> owned;  // the registry's, by owner
    for (const auto& m : service.api().methods()) owned[m.owner].insert(m.name);
    for (const auto& e : service.api().events()) owned[e.owner].insert(e.name);
    owned.erase("api");      // the front end's own (server.auth, subscribe)
    owned.erase("service");  // start-up's own (server.info)
    const auto map = component_map();
    ASSERT_GE(map.size(), 4u) << "docs/layout.md: no component map read";
    for (const auto& [owner, names] : owned) {
        ASSERT_TRUE(map.contains(owner)) << owner << " registers endpoints but has no row";
        EXPECT_EQ(map.at(owner).endpoints, names) << owner;
    }
    for (const auto& [component, row] : map) {
        EXPECT_TRUE(owned.contains(component)) << component << " is in the map but registers nothing";
        EXPECT_TRUE(fs::is_directory(source_path(row.folder))) << row.folder;
    }
}

// The service in this process: started, its io_context on a thread of its own.
class InProcessService {
  public:
    explicit InProcessService(const fs::path& config)
        : service_(io_, daemon::service::load_service_config(config.string())) {}
    ~InProcessService() {
        service_.stop();
        io_.stop();
        if (thread_.joinable()) thread_.join();
    }
    Service& operator*() { return service_; }
    void start() {
        service_.start();
        thread_ = std::thread([this] { io_.run(); });
    }

  private:
    boost::asio::io_context io_;
    Service service_;
    std::thread thread_;
};

TEST_F(ServiceTest, AStartGateHoldsEveryStartUntilItOpens) {
    InProcessService service(write_config());
    std::atomic<bool> closed{true};
    std::atomic<int> asked{0};
    (*service).printer().add_start_gate([&](const daemon::jobs::JobRecord&) -> std::optional<std::string> {
        ++asked;
        if (closed) return "the test's gate is closed";
        return std::nullopt;
    });
    service.start();
    auto c = client();

    // Submitted with start: planned, then held at the gate, not started.
    const std::int64_t id = submit_bar(c, true);
    json job = wait_for_state(c, id, "planned");
    ASSERT_EQ(job.value("state", ""), "planned") << job.dump();
    ASSERT_TRUE(eventually([&] { return asked >= 1; }));
    EXPECT_EQ(c.call("job.get", {{"job", id}}).value("state", ""), "planned");

    // job.start: refused with the gate's reason, the job still planned.
    try {
        c.call("job.start", {{"job", id}});
        ADD_FAILURE() << "job.start passed a closed gate";
    } catch (const api::ApiCallError& e) {
        EXPECT_EQ(e.code(), api::errc::conflict);
        EXPECT_NE(std::string(e.what()).find("job " + std::to_string(id) +
                                             " cannot start: the test's gate is closed"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(c.call("job.get", {{"job", id}}).value("state", ""), "planned");

    // Open: the same call starts it.
    closed = false;
    job = c.call("job.start", {{"job", id}});
    EXPECT_EQ(job.value("state", ""), "starting") << job.dump();
    c.call("job.abort", {{"job", id}});
    job = wait_for_state(c, id, "aborted");
    EXPECT_EQ(job.value("state", ""), "aborted") << job.dump();
}

}  // namespace service_components_test
}  // namespace fibrecell::test
