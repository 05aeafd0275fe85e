#include "drivers/sim/rws/rws_routes.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

#include "drivers/abb/rws/rws_json.hpp"
#include "drivers/abb/rws/url.hpp"

namespace fibrecell::drivers::sim::rws {

// The wire's forms, shared with the client (drivers/abb/rws).
namespace json = abb::rws::json;
using abb::rws::form_value;
using abb::rws::FormFields;
using abb::rws::parse_form;
using abb::rws::percent_decode;

namespace {

using json::Json;

// Codes reported in status bodies. Not the controller's real return codes: clients of the
// simulator go by the HTTP status and the message.
constexpr long long code_refused = -1;
constexpr long long code_no_mastership = -2;
constexpr long long code_not_found = -3;
constexpr long long code_bad_request = -4;

RouteReply status_reply(unsigned status, long long code, std::string_view msg) {
    return {status, json::wire_text(json::status_document(code, msg))};
}

RouteReply no_content() {
    return {204, "", "application/json"};
}

RouteReply state_reply(std::string_view host, std::string_view base, Json items) {
    return {200, json::wire_text(json::state_document(
                     "http://" + std::string(host) + std::string(base), std::move(items)))};
}

std::vector<std::string> split_path(std::string_view path) {
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < path.size()) {
        if (path[i] == '/') {
            ++i;
            continue;
        }
        const auto end = path.find('/', i);
        const auto seg = path.substr(i, end == std::string_view::npos ? path.npos : end - i);
        out.push_back(percent_decode(seg, false));
        i = end == std::string_view::npos ? path.size() : end;
    }
    return out;
}

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(a[i])) !=
            std::tolower(static_cast<unsigned char>(b[i])))
            return false;
    return true;
}

// HOME-relative path of `segments`, or nothing when a segment is empty, "." or "..".
std::optional<std::string> home_path(const std::vector<std::string>& segments, std::size_t from) {
    if (from >= segments.size()) return std::nullopt;
    std::string out;
    for (std::size_t i = from; i < segments.size(); ++i) {
        const std::string& s = segments[i];
        if (s.empty() || s == "." || s == ".." || s.find('\\') != std::string::npos)
            return std::nullopt;
        if (!out.empty()) out.push_back('/');
        out += s;
    }
    return out;
}

// "$HOME/x.mod", "HOME:/x.mod" or "HOME:x.mod" -> "x.mod".
std::optional<std::string> module_file(std::string_view modulepath) {
    std::string_view rest;
    if (modulepath.size() > 6 && iequals(modulepath.substr(0, 6), "$HOME/"))
        rest = modulepath.substr(6);
    else if (modulepath.size() > 5 && iequals(modulepath.substr(0, 5), "HOME:"))
        rest = modulepath.substr(modulepath[5] == '/' ? 6 : 5);
    else
        return std::nullopt;
    return home_path(split_path(rest), 0);
}

RouteReply mastership_refusal(const MastershipGate& gate) {
    if (gate.held_elsewhere())
        return status_reply(403, code_no_mastership, "RAPID mastership is held by another client");
    return status_reply(403, code_no_mastership,
                        "RAPID mastership is not held by this client (request it first)");
}

struct Router {
    const RouteRequest& req;
    const FormFields query;
    const FormFields form;
    RwsBackend& backend;
    MastershipGate& gate;
    std::string_view task;

    std::string action() const { return form_value(query, "action"); }
    bool is(std::string_view m) const { return req.method == m; }

    RouteReply files(const std::vector<std::string>& seg) {
        // /fileservice/$HOME/<path>
        if (seg.size() < 3 || !iequals(seg[1], "$HOME"))
            return status_reply(404, code_not_found, "only $HOME is served by this controller");
        const auto path = home_path(seg, 2);
        if (!path) return status_reply(400, code_bad_request, "invalid file path");
        if (is("PUT")) {
            const bool created = backend.write_file(*path, std::string(req.body));
            return {created ? 201u : 200u, "", "application/json"};
        }
        if (is("GET")) {
            const auto contents = backend.read_file(*path);
            if (!contents)
                return status_reply(404, code_not_found, "file HOME:/" + *path + " does not exist");
            return {200, *contents, "application/octet-stream"};
        }
        return status_reply(405, code_bad_request, "method not allowed on /fileservice");
    }

    RouteReply task_actions() {
        const std::string a = action();
        if (a == "loadmod") {
            const std::string mp = form_value(form, "modulepath");
            const auto path = module_file(mp);
            if (!path)
                return status_reply(400, code_bad_request,
                                    "modulepath '" + mp + "' is not a file under $HOME");
            if (!gate.held_by_caller()) return mastership_refusal(gate);
            backend.load_module(*path, form_value(form, "replace", "false") == "true");
            return no_content();
        }
        if (a == "unloadmod") {
            const std::string module = form_value(form, "module");
            if (module.empty()) return status_reply(400, code_bad_request, "module is missing");
            if (!gate.held_by_caller()) return mastership_refusal(gate);
            backend.unload_module(module);
            return no_content();
        }
        return status_reply(400, code_bad_request, "unknown task action '" + a + "'");
    }

    RouteReply modules() {
        if (form_value(query, "task") != task)
            return status_reply(404, code_not_found, "no task '" + form_value(query, "task") + "'");
        Json items = Json::array();
        for (const ModuleInfo& m : backend.modules()) {
            Json i = json::item("rap-module-info-li", m.name);
            i["name"] = m.name;
            i["type"] = m.type;
            items.push_back(std::move(i));
        }
        return state_reply(req.host, "/rw/rapid/", std::move(items));
    }

    RouteReply build_errors() {
        Json items = Json::array();
        for (const BuildError& e : backend.build_log()) {
            Json i = json::item("rap-builderrs", "builderrs");
            i["ModuleName"] = e.module;
            i["row"] = std::to_string(e.row);
            i["column"] = std::to_string(e.column);
            i["error"] = e.message;
            items.push_back(std::move(i));
        }
        return state_reply(req.host, "/rw/rapid/", std::move(items));
    }

    RouteReply execution() {
        if (is("GET")) {
            const ExecutionInfo e = backend.execution();
            Json i = json::item("rap-execution", "execution");
            i["ctrlexecstate"] = std::string(to_string(e.state));
            i["cycle"] = e.cycle;
            return state_reply(req.host, "/rw/rapid/", Json::array({std::move(i)}));
        }
        if (!is("POST")) return status_reply(405, code_bad_request, "method not allowed");
        const std::string a = action();
        if (a == "start") {
            StartOptions o;
            o.regain = form_value(form, "regain", o.regain);
            o.execmode = form_value(form, "execmode", o.execmode);
            o.cycle = form_value(form, "cycle", o.cycle);
            o.condition = form_value(form, "condition", o.condition);
            o.stopatbp = form_value(form, "stopatbp", o.stopatbp);
            o.alltaskbytsp = form_value(form, "alltaskbytsp", o.alltaskbytsp);
            backend.start(o);
            return no_content();
        }
        if (a == "stop") {
            backend.stop();
            return no_content();
        }
        if (a == "resetpp") {
            if (!gate.held_by_caller()) return mastership_refusal(gate);
            backend.reset_pp();
            return no_content();
        }
        return status_reply(400, code_bad_request, "unknown execution action '" + a + "'");
    }

    RouteReply mastership() {
        if (!is("POST")) return status_reply(405, code_bad_request, "method not allowed");
        const std::string a = action();
        if (a == "request") {
            if (!gate.request())
                return status_reply(403, code_no_mastership,
                                    "RAPID mastership is held by another client");
            return no_content();
        }
        if (a == "release") {
            gate.release();
            return no_content();
        }
        return status_reply(400, code_bad_request, "unknown mastership action '" + a + "'");
    }

    RouteReply symbol(const std::vector<std::string>& seg) {
        // /rw/rapid/symbol/data/RAPID/<task>/<module>/<name>
        if (seg.size() != 8 || seg[4] != "RAPID")
            return status_reply(404, code_not_found, "no such symbol path");
        if (seg[5] != task) return status_reply(404, code_not_found, "no task '" + seg[5] + "'");
        const std::string& module = seg[6];
        const std::string& name = seg[7];
        if (is("GET")) {
            Json i = json::item("rap-data", "RAPID/" + seg[5] + "/" + module + "/" + name);
            i["value"] = backend.read_symbol(module, name);
            return state_reply(req.host, "/rw/rapid/", Json::array({std::move(i)}));
        }
        if (is("POST") && action() == "set") {
            if (!gate.held_by_caller()) return mastership_refusal(gate);
            if (!std::any_of(form.begin(), form.end(),
                             [](const auto& f) { return f.first == "value"; }))
                return status_reply(400, code_bad_request, "value is missing");
            backend.write_symbol(module, name, form_value(form, "value"));
            return no_content();
        }
        return status_reply(400, code_bad_request, "unsupported symbol request");
    }

    RouteReply dispatch() {
        const auto q = req.target.find('?');
        const auto seg = split_path(req.target.substr(0, q));
        if (!seg.empty() && seg[0] == "fileservice") return files(seg);
        if (seg.size() < 2 || seg[0] != "rw")
            return status_reply(404, code_not_found, "no resource " + std::string(req.target));
        if (seg[1] == "mastership" && seg.size() == 2) return mastership();
        if (seg[1] == "panel" && seg.size() == 3 && seg[2] == "ctrlstate" && is("GET")) {
            Json i = json::item("pnl-ctrlstate", "ctrlstate");
            i["ctrlstate"] = std::string(to_string(backend.controller_state()));
            return state_reply(req.host, "/rw/panel/", Json::array({std::move(i)}));
        }
        if (seg[1] == "rapid" && seg.size() >= 3) {
            if (seg[2] == "execution" && seg.size() == 3) return execution();
            if (seg[2] == "modules" && seg.size() == 3 && is("GET")) return modules();
            if (seg[2] == "symbol" && seg.size() >= 4 && seg[3] == "data") return symbol(seg);
            if (seg[2] == "tasks" && seg.size() >= 4) {
                if (seg[3] != task)
                    return status_reply(404, code_not_found, "no task '" + seg[3] + "'");
                if (seg.size() == 4 && is("POST")) return task_actions();
                if (seg.size() == 6 && seg[4] == "program" && seg[5] == "builderror" && is("GET"))
                    return build_errors();
            }
        }
        return status_reply(404, code_not_found, "no resource " + std::string(req.target));
    }
};

}  // namespace

RouteReply route(const RouteRequest& request, RwsBackend& backend, MastershipGate& mastership,
                 std::string_view task) {
    const auto q = request.target.find('?');
    Router r{
        request,
        parse_form(q == std::string_view::npos ? std::string_view() : request.target.substr(q + 1)),
        request.method == "POST" ? parse_form(request.body) : FormFields{},
        backend,
        mastership,
        task};
    try {
        return r.dispatch();
    } catch (const BackendError& e) {
        return status_reply(static_cast<unsigned>(e.http_status()),
                            e.rws_code() != -1       ? e.rws_code()
                            : e.http_status() == 404 ? code_not_found
                                                     : code_refused,
                            e.what());
    }
}

}  // namespace fibrecell::drivers::sim::rws
