#include "cli/common_options.hpp"

#include <cmath>
#include <cstdlib>

namespace skinspec::cli {

CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& help) {
    return command.add_option("--seed", seed, help)->capture_default_str()->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 63));
}

void require_finite_numbers(CLI::App& app) {
    static const CLI::Validator finite(
        [](std::string& text) {
            // As CLI11 reads it: strtod takes nan, inf and overflows (1e400) to inf.
            char* end = nullptr;
            const double number = std::strtod(text.c_str(), &end);
            const bool whole = end != text.c_str() && *end == '\0';
            return whole && !std::isfinite(number) ? "'" + text + "' is not a finite number" : std::string();
        },
        "", "FINITE");
    // An empty text is no file name, colour space or list ("--output ''" ran and wrote nothing).
    static const CLI::Validator not_empty([](std::string& text) { return text.empty() ? std::string("an empty value is not allowed") : std::string(); }, "",
                                          "NONEMPTY");
    for (auto* option : app.get_options()) {
        if (option->get_type_name().starts_with("FLOAT")) option->check(finite);
        if (option->get_type_name().starts_with("TEXT")) option->check(not_empty);
    }
    for (auto* command : app.get_subcommands({})) require_finite_numbers(*command);
}

CLI::Option* add_overwrite_flag(CLI::App& command, bool& overwrite, const std::string& help) {
    return command.add_flag("--overwrite,--force", overwrite, help);
}

}  // namespace skinspec::cli
