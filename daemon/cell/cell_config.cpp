#include "daemon/cell/cell_config.hpp"

#include "config/yaml_section.hpp"

namespace fibrecell::daemon {

CellConfig load_cell_config(const std::string& path,
                            const std::function<void(config::Section& root)>& service) {
    auto root = config::Section::load_file(path);
    CellConfig c;
    c.name = root.get_or<std::string>("name", c.name);
    c.log_level =
        root.choice("log_level", c.log_level, {"trace", "debug", "info", "warn", "error", "off"});
    c.state_dir = root.path_or("state_dir", c.state_dir);
    c.simulated = root.get_or<bool>("simulated", c.simulated);
    c.extruder = drivers::load_extruder_config(root.section("extruder"));
    c.robot = drivers::abb::load_robot_config(root.section("robot"));
    c.rws = drivers::abb::rws::load_rws_config(root.section("rws"));
    c.robot_io = drivers::abb::load_robot_io_config(root.section("robot_io"));
    c.simulation = load_simulation_config(root.section("simulation"));
    c.part_limits = load_part_limits(root.section("part_limits"));
    if (service) {
        service(root);
    } else {
        for (const char* key : service_sections) root.node(key);
    }
    root.finish();
    return c;
}

}  // namespace fibrecell::daemon
