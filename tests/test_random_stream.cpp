#include <catch2/catch.hpp>

#include "transport/random_stream.hpp"

using namespace skinspec;

TEST_CASE("streams are reproducible and independent per (seed, wavelength, batch)", "[random_stream]") {
    auto a = RandomStream::for_batch(1, 550.0, 3);
    auto b = RandomStream::for_batch(1, 550.0, 3);
    auto c = RandomStream::for_batch(1, 550.0, 4);
    auto d = RandomStream::for_batch(1, 560.0, 3);
    auto e = RandomStream::for_batch(2, 550.0, 3);
    int same_c = 0, same_d = 0, same_e = 0;
    double sum = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const double x = a.uniform();
        CHECK(x == b.uniform());
        CHECK(x >= 0.0);
        CHECK(x < 1.0);
        same_c += x == c.uniform();
        same_d += x == d.uniform();
        same_e += x == e.uniform();
        sum += x;
    }
    CHECK(same_c < 5);
    CHECK(same_d < 5);
    CHECK(same_e < 5);
    CHECK(sum / 1e5 == Approx(0.5).margin(0.005));  // mean of U(0,1), 5 sigma = 0.0046
}
