#include "spectral/image_files.hpp"

#include <cstdlib>
#include <future>

#include <dlfcn.h>

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/memory_budget.hpp"

namespace skinspec {
namespace {

// Where the module may be: $SKINSPEC_IMAGE_MODULE, next to the running program, or where the build put it.
std::vector<std::filesystem::path> module_candidates() {
    std::vector<std::filesystem::path> out;
    if (const char* env = std::getenv("SKINSPEC_IMAGE_MODULE"); env && *env) out.emplace_back(env);
    std::error_code error;
    const auto program = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        out.push_back(program.parent_path() / "libskinspec_images.so");
        out.push_back(program.parent_path().parent_path() / "lib" / "skinspec" / "libskinspec_images.so");
    }
    out.emplace_back(SKINSPEC_IMAGE_MODULE_PATH);
    return out;
}

const ImageModuleFunctions& load_module() {
    std::string tried;
    for (const auto& candidate : module_candidates()) {
        tried += (tried.empty() ? "" : ", ") + candidate.string();
        if (!std::filesystem::is_regular_file(candidate)) continue;
        void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) throw ImageModuleError("image module " + candidate.string() + " cannot be loaded: " + dlerror());
        using Entry = const ImageModuleFunctions* (*)();
        const auto entry = reinterpret_cast<Entry>(dlsym(handle, "skinspec_image_module"));
        if (!entry) throw ImageModuleError("image module " + candidate.string() + " has no entry point skinspec_image_module");
        const ImageModuleFunctions* functions = entry();
        if (functions->interface_version != image_module_interface_version) {
            throw ImageModuleError("image module " + candidate.string() + " has interface " + std::to_string(functions->interface_version) +
                                     ", this program needs " + std::to_string(image_module_interface_version) + " (rebuild)");
        }
        return *functions;
    }
    throw ImageModuleError("image support (libskinspec_images.so) not found; looked in: " + tried);
}

// The module, loaded once on a thread of its own; its failure is rethrown to every use.
const std::shared_future<const ImageModuleFunctions*>& loading() {
    static const std::shared_future<const ImageModuleFunctions*> loaded = std::async(std::launch::async, [] { return &load_module(); }).share();
    return loaded;
}

const ImageModuleFunctions& module() { return *loading().get(); }

}  // namespace

void load_image_module_in_background() { loading(); }

DataImage read_data_image(const std::filesystem::path& file) {
    std::error_code error;
    const auto status = std::filesystem::status(file, error);
    if (!std::filesystem::exists(status)) throw InputError(file.string() + ": image not found");
    if (!std::filesystem::is_regular_file(status)) throw InputError(file.string() + ": is " + file_kind(status.type()) + ", not an image");
    DataImage out;
    if (const auto error = module().read(file.string(), available_memory_bytes(), out); !error.empty()) throw InputError(file.string() + ": " + error);
    return out;
}

void write_image_file(const std::filesystem::path& file, const DataImage& image, PixelFormat format, const ImageAttributes& attributes,
                      const std::filesystem::path& reported_name) {
    if (const auto error = module().write(file.string(), image, format, attributes); !error.empty()) {
        throw InputError(reported_name.string() + ": cannot be written (" + error + ")");
    }
}

void render_text(DataImage& image, int x, int y, const std::string& text, int font_px, const std::string& font, const std::array<float, 3>& colour) {
    if (const auto error = module().render_text(image, x, y, text, font_px, font, colour); !error.empty()) {
        throw InputError("cannot draw labels: " + error + " (install fonts-dejavu-core)");
    }
}

}  // namespace skinspec
