// Reconstruction filters: unit integral, the stated support, shape.
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "core/sampling/filters.hpp"

using namespace weft;

namespace {

const FilterKind kAll[] = {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian,
                           FilterKind::Mitchell, FilterKind::BSpline, FilterKind::RaisedCosine};

double integral1D(const ReconstructionFilter& f) {
    const int n = 200000;
    const double a = -f.radius() - 1, b = f.radius() + 1, h = (b - a) / n;
    double s = 0;
    for (int i = 0; i < n; ++i) s += f.eval1D(a + (i + 0.5) * h) * h;
    return s;
}

}  // namespace

TEST(Filters, EachIntegratesToOneAtItsOwnAndOtherRadii) {
    for (FilterKind k : kAll)
        for (double r : {0.0, 0.75, 2.5}) {
            const ReconstructionFilter f(k, r);
            EXPECT_NEAR(integral1D(f), 1.0, 5e-5) << int(k) << " r=" << r;
        }
}

TEST(Filters, TwoDimensionalFilterIntegratesToOne) {
    for (FilterKind k : kAll) {
        const ReconstructionFilter f(k);
        const int n = 400;
        const double h = 2 * f.radius() / n;
        double s = 0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) s += f.eval(-f.radius() + (i + 0.5) * h, -f.radius() + (j + 0.5) * h) * h * h;
        EXPECT_NEAR(s, 1.0, 1e-4) << int(k);
    }
}

TEST(Filters, KnownSupportZeroOutsideNonZeroInside) {
    const double expected[] = {0.5, 1.0, 1.5, 2.0, 2.0, 1.0};
    for (int i = 0; i < 6; ++i) {
        const ReconstructionFilter f(kAll[i]);
        EXPECT_DOUBLE_EQ(f.radius(), expected[i]);
        EXPECT_EQ(f.eval1D(f.radius()), 0.0);
        EXPECT_EQ(f.eval1D(-f.radius() - 1e-9), 0.0);
        EXPECT_EQ(f.eval1D(7.0), 0.0);
        EXPECT_NE(f.eval1D(0.98 * f.radius()), 0.0) << i;
        EXPECT_GT(f.eval1D(0), 0.0);
        EXPECT_DOUBLE_EQ(f.eval1D(0.3), f.eval1D(-0.3));
    }
}

TEST(Filters, ShapesAreTheTextbookOnes) {
    EXPECT_DOUBLE_EQ(ReconstructionFilter(FilterKind::Box).eval1D(0.4), 1.0);
    EXPECT_DOUBLE_EQ(ReconstructionFilter(FilterKind::Tent).eval1D(0.25), 0.75);
    EXPECT_NEAR(ReconstructionFilter(FilterKind::RaisedCosine).eval1D(0.5), 0.5, 1e-15);  // (1 + cos(pi/2)) / 2
    // Mitchell-Netravali (1/3, 1/3): 8/9 at 0, a negative lobe in (1, 2) (scaled radius 2), cubic B-spline 2/3 at 0.
    const ReconstructionFilter m(FilterKind::Mitchell), b(FilterKind::BSpline);
    EXPECT_NEAR(m.eval1D(0), 8.0 / 9.0, 1e-12);
    EXPECT_LT(m.eval1D(1.5), 0.0);
    EXPECT_NEAR(b.eval1D(0), 2.0 / 3.0, 1e-12);
    EXPECT_GT(b.eval1D(1.5), 0.0);
    EXPECT_NEAR(b.eval1D(1.0), 1.0 / 6.0, 1e-12);
}

TEST(Filters, NamesRoundTripAndUnknownIsAnError) {
    EXPECT_EQ(ReconstructionFilter::kindFromName("raised_cosine"), FilterKind::RaisedCosine);
    EXPECT_EQ(ReconstructionFilter::kindFromName("mitchell"), FilterKind::Mitchell);
    EXPECT_THROW(ReconstructionFilter::kindFromName("lanczos"), Error);
}
