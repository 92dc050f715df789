#include "appearance/image_convolution.hpp"

#include <complex>
#include <mutex>
#include <stdexcept>

#include <fftw3.h>

namespace skinspec {
namespace {
// FFTW's planner is not thread-safe: plans are made and destroyed under one lock.
std::mutex& planner_lock() {
    static std::mutex lock;
    return lock;
}
struct FftwFree {
    void operator()(void* p) const { fftw_free(p); }
};
}  // namespace

struct ImageConvolver::Impl {
    int width, height, reach_x, reach_y, nx, ny, ncx;
    std::unique_ptr<double[], FftwFree> real;
    std::unique_ptr<fftw_complex[], FftwFree> image_hat, kernel_hat;
    fftw_plan forward_kernel = nullptr, backward = nullptr;
};

ImageConvolver::ImageConvolver(const std::vector<double>& image, int width, int height, int reach_x, int reach_y)
    : impl_(std::make_unique<Impl>()) {
    if (width <= 0 || height <= 0 || image.size() != static_cast<std::size_t>(width) * height || reach_x < 0 || reach_y < 0) {
        throw std::invalid_argument("ImageConvolver: image size or reach");
    }
    auto& s = *impl_;
    s.width = width;
    s.height = height;
    s.reach_x = reach_x;
    s.reach_y = reach_y;
    s.nx = width + 2 * reach_x;  // no wrap-around between the image and any kernel offset
    s.ny = height + 2 * reach_y;
    s.ncx = s.nx / 2 + 1;
    const std::size_t n_real = static_cast<std::size_t>(s.nx) * s.ny, n_complex = static_cast<std::size_t>(s.ny) * s.ncx;
    s.real.reset(static_cast<double*>(fftw_malloc(sizeof(double) * n_real)));
    s.image_hat.reset(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * n_complex)));
    s.kernel_hat.reset(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * n_complex)));
    fftw_plan forward_image;
    {
        const std::lock_guard guard(planner_lock());
        forward_image = fftw_plan_dft_r2c_2d(s.ny, s.nx, s.real.get(), s.image_hat.get(), FFTW_ESTIMATE);
        s.forward_kernel = fftw_plan_dft_r2c_2d(s.ny, s.nx, s.real.get(), s.kernel_hat.get(), FFTW_ESTIMATE);
        s.backward = fftw_plan_dft_c2r_2d(s.ny, s.nx, s.kernel_hat.get(), s.real.get(), FFTW_ESTIMATE);
    }
    std::fill(s.real.get(), s.real.get() + n_real, 0.0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) s.real[static_cast<std::size_t>(y) * s.nx + x] = image[static_cast<std::size_t>(y) * width + x];
    }
    fftw_execute(forward_image);
    const std::lock_guard guard(planner_lock());
    fftw_destroy_plan(forward_image);
}

ImageConvolver::~ImageConvolver() {
    const std::lock_guard guard(planner_lock());
    if (impl_->forward_kernel) fftw_destroy_plan(impl_->forward_kernel);
    if (impl_->backward) fftw_destroy_plan(impl_->backward);
}

std::vector<double> ImageConvolver::convolve(const std::vector<double>& kernel) const {
    auto& s = *impl_;
    const int kw = 2 * s.reach_x + 1, kh = 2 * s.reach_y + 1;
    if (kernel.size() != static_cast<std::size_t>(kw) * kh) throw std::invalid_argument("ImageConvolver: kernel size");
    const std::size_t n_real = static_cast<std::size_t>(s.nx) * s.ny, n_complex = static_cast<std::size_t>(s.ny) * s.ncx;
    std::fill(s.real.get(), s.real.get() + n_real, 0.0);
    // Offsets wrap around the origin of the cyclic transform.
    for (int j = -s.reach_y; j <= s.reach_y; ++j) {
        for (int i = -s.reach_x; i <= s.reach_x; ++i) {
            s.real[static_cast<std::size_t>((j + s.ny) % s.ny) * s.nx + static_cast<std::size_t>((i + s.nx) % s.nx)] =
                kernel[static_cast<std::size_t>(j + s.reach_y) * kw + static_cast<std::size_t>(i + s.reach_x)];
        }
    }
    fftw_execute_dft_r2c(s.forward_kernel, s.real.get(), s.kernel_hat.get());
    const double scale = 1.0 / static_cast<double>(n_real);
    for (std::size_t k = 0; k < n_complex; ++k) {
        const std::complex<double> a(s.image_hat[k][0], s.image_hat[k][1]), b(s.kernel_hat[k][0], s.kernel_hat[k][1]);
        const auto p = a * b * scale;
        s.kernel_hat[k][0] = p.real();
        s.kernel_hat[k][1] = p.imag();
    }
    fftw_execute_dft_c2r(s.backward, s.kernel_hat.get(), s.real.get());
    std::vector<double> out(static_cast<std::size_t>(s.width) * s.height);
    for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) out[static_cast<std::size_t>(y) * s.width + x] = s.real[static_cast<std::size_t>(y) * s.nx + x];
    }
    return out;
}

}  // namespace skinspec
