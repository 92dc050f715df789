#pragma once
// The one exception type for bad user input (files, options, presets). Its message is a complete,
// single-line explanation naming where (file:line or option), the field, the value and what is allowed.
#include <stdexcept>
#include <string>

namespace skinspec {

class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace skinspec
