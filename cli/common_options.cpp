#include "cli/common_options.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "transport/spectral_request.hpp"

namespace skinspec::cli {

CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& help) {
    return command.add_option("--seed", seed, help)->capture_default_str()->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 63));
}

CLI::Option* add_ray_count_option(CLI::App& command, const std::string& name, std::uint64_t& rays, const std::string& help) {
    return command.add_option(name, rays, help + " (at least " + std::to_string(minimum_rays_per_wavelength) + ": the standard error comes from the rays' spread)")
        ->check(CLI::Range(minimum_rays_per_wavelength, maximum_rays_per_wavelength));
}

void check_option_values(CLI::App& app) {
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
    // Whole numbers are decimal, as a person writes them: spaces around dropped, leading zeros too (CLI11 reads 010 as
    // octal 8 and refuses 08), 0x / 0o / 0b prefixes refused; 1e3 written as a real is 1000.
    static const CLI::Validator whole(
        [](std::string& text) {
            const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
            text = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
            const std::size_t sign = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
            if (text.size() > sign + 1 && text[sign] == '0') {
                const char base = static_cast<char>(std::tolower(static_cast<unsigned char>(text[sign + 1])));
                if (base == 'x' || base == 'o' || base == 'b') return "'" + text + "' is not a decimal whole number";
                const auto digits = text.find_first_not_of('0', sign);
                if (digits != std::string::npos && std::isdigit(static_cast<unsigned char>(text[digits])) &&
                    text.find_first_not_of("0123456789", sign) == std::string::npos) {
                    text = text.substr(0, sign) + text.substr(digits);
                } else if (digits == std::string::npos) {
                    text = text.substr(0, sign) + "0";
                }
            }
            char* end = nullptr;
            const double number = std::strtod(text.c_str(), &end);
            const bool written_as_real = end != text.c_str() && *end == '\0' && text.find_first_of(".eE") != std::string::npos;
            if (written_as_real && std::isfinite(number) && number == std::trunc(number) && std::abs(number) < 9.2e18) {
                text = std::to_string(static_cast<long long>(number));  // 1e3 -> 1000, as CLI11 reads whole numbers
            }
            return std::string();
        },
        "", "WHOLE");
    static const CLI::Validator unsigned_count(
        [](std::string& text) { return text.starts_with("-") ? "'" + text + "' is negative (a count or size, >= 0)" : std::string(); }, "",
        "UNSIGNED");
    for (auto* option : app.get_options()) {
        const auto type = option->get_type_name();
        if (type.starts_with("FLOAT")) option->check(finite);
        if (type.starts_with("TEXT")) option->check(not_empty);
        if (type.starts_with("INT") || type.starts_with("UINT")) option->transform(whole);
        if (type.starts_with("UINT")) option->check(unsigned_count);
    }
    for (auto* command : app.get_subcommands({})) check_option_values(*command);
}

CLI::Option* add_overwrite_flag(CLI::App& command, bool& overwrite, const std::string& help) {
    return command.add_flag("--overwrite,--force", overwrite, help);
}

std::vector<std::string> given_options(const CLI::App& command, const std::vector<std::string>& names) {
    std::vector<std::string> out;
    for (const auto& name : names) {
        const auto* option = command.get_option_no_throw(name);
        if (option && option->count() > 0) out.push_back(name);
    }
    return out;
}

std::vector<std::string> given_sampling_options(const CLI::App& command) { return given_options(command, {"--seed", "--max-rays"}); }

}  // namespace skinspec::cli
