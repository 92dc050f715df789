#pragma once
// Reader for skinspec's own table format (docs/DATA_FORMAT.md): '# key: value' header lines (format
// version, title, source, units, domain_nm, outside_domain, notes), one line of column names with units in
// the names, then comma-separated numeric rows. The first column is wavelength_nm.
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

class DataTable {
public:
    static DataTable read(const std::filesystem::path& file);

    // Header value for `key`; InputError naming the file when absent.
    const std::string& metadata(std::string_view key) const;
    bool has_metadata(std::string_view key) const;
    const std::vector<std::string>& column_names() const { return column_names_; }
    std::span<const double> column(std::string_view name) const;
    OutOfRangePolicy outside() const { return outside_; }
    const std::filesystem::path& file() const { return file_; }

    // wavelength_nm against `column`, with the table's own out-of-range policy.
    TabulatedSpectrum spectrum(std::string_view column_name, std::string spectrum_name) const;

private:
    std::filesystem::path file_;
    std::map<std::string, std::string, std::less<>> metadata_;
    std::vector<std::string> column_names_;
    std::vector<std::vector<double>> columns_;
    OutOfRangePolicy outside_ = OutOfRangePolicy::error;
};

}  // namespace skinspec
