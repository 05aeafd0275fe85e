#pragma once
// The cell YAML's `print:` section (docs/service.md, "Configuration").

#include "config/yaml_section.hpp"
#include "daemon/printer/print_runner.hpp"

namespace fibrecell::daemon::printer {

// Throws config::ConfigError naming the key.
PrintRunnerOptions load_print_options(config::Section section);

}  // namespace fibrecell::daemon::printer
