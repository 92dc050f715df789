#include "cli/common_options.hpp"

namespace skinspec::cli {

CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& help) {
    return command.add_option("--seed", seed, help)->capture_default_str()->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 63));
}

CLI::Option* add_overwrite_flag(CLI::App& command, bool& overwrite, const std::string& help) {
    return command.add_flag("--overwrite,--force", overwrite, help);
}

}  // namespace skinspec::cli
