#pragma once
// The `rws:` section of the cell YAML: where the IRC5's Robot Web Services are, who logs in, and
// the folder in HOME: that receives a job's chunk modules (FcMain's sFcJobDir). docs/rws-link.md.

#include "config/yaml_section.hpp"
#include "drivers/abb/rws/rws_client.hpp"

#include <string>

namespace fibrecell::drivers::abb::rws {

struct RwsLinkConfig {
    RwsClientConfig client;
    // Job folder relative to HOME: (no "..", '/'-separated); FcMain gets "HOME:/<job_dir>".
    std::string job_dir = "fibrecell/job";
};

// Reads and checks the section (ranges, unknown keys); throws config::ConfigError naming the key.
RwsLinkConfig load_rws_config(config::Section s);

}  // namespace fibrecell::drivers::abb::rws
