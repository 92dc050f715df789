#pragma once
// Linear (not cyclic) 2-D convolution of one image with many kernels through FFTW: the image's transform is
// computed once, each kernel costs one forward and one inverse real transform. Used by the lit swatches
// (light * reflectance profile) and the profile fit (incident power * quantisation tents).
#include <memory>
#include <vector>

namespace skinspec {

class ImageConvolver {
public:
    // `image` is width x height, row-major; kernels cover offsets |i| <= reach_x, |j| <= reach_y.
    ImageConvolver(const std::vector<double>& image, int width, int height, int reach_x, int reach_y);
    ~ImageConvolver();
    ImageConvolver(const ImageConvolver&) = delete;
    ImageConvolver& operator=(const ImageConvolver&) = delete;

    // out(x, y) = sum_{i,j} kernel(i, j) image(x - i, y - j) over the image (zero outside it), for every pixel
    // of the image. `kernel` is (2 reach_x + 1) x (2 reach_y + 1), row-major, offset (-reach_x, -reach_y) first.
    // Uses the object's buffers: one call at a time per object.
    std::vector<double> convolve(const std::vector<double>& kernel) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace skinspec
