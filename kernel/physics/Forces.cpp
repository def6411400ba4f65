#include "physics/Forces.h"

#include "model/Error.h"
#include "physics/ThreadPool.h"

#include <cassert>
#include <cmath>
#include <limits>
#include <string>

namespace netsculpt {

namespace {

bool positiveFinite(double value) {
    return std::isfinite(value) && value > 0;
}

[[noreturn]] void badSystem(const std::string& what) {
    throw UserError("mass-spring system: " + what);
}

void checkSizes(const MassSpringSystem& system) {
    const std::size_t knots = system.knotCount(), bars = system.barCount();
    auto check = [](std::size_t size, std::size_t expected, const char* name) {
        if (size != expected)
            badSystem(std::string(name) + " has " + std::to_string(size) + " entries, expected " +
                      std::to_string(expected));
    };
    check(system.mass.size(), knots, "mass");
    check(system.fixed.size(), knots, "fixed");
    check(system.barB.size(), bars, "barB");
    check(system.restLength.size(), bars, "restLength");
    check(system.kTension.size(), bars, "kTension");
    check(system.kCompression.size(), bars, "kCompression");
    if (knots >= std::numeric_limits<std::uint32_t>::max() / 2 ||
        bars >= std::numeric_limits<std::uint32_t>::max() / 2)
        badSystem("too many knots or bars (" + std::to_string(knots) + ", " + std::to_string(bars) +
                  ")");
}

} // namespace

Vec3 validatedWindDirection(const Wind& wind) {
    const double length = wind.direction.norm();
    if (!wind.direction.isFinite() || !(length > 0))
        throw UserError("wind direction must be a finite non-zero vector, got (" +
                        formatNumber(wind.direction.x) + ", " + formatNumber(wind.direction.y) +
                        ", " + formatNumber(wind.direction.z) + ")");
    if (!std::isfinite(wind.pressure) || wind.pressure < 0)
        throw UserError("wind pressure must be finite and >= 0 N/m, got " +
                        formatNumber(wind.pressure));
    return wind.direction / length;
}

ForceField::ForceField(const MassSpringSystem& system) {
    checkSizes(system);
    const std::size_t knots = system.knotCount(), bars = system.barCount();
    const double g = system.gravity.norm();
    if (!system.gravity.isFinite() || !(g > 0))
        badSystem("gravity must be finite and non-zero, got |g| = " + formatNumber(g));

    weight_.resize(knots);
    inverseWeight_.resize(knots);
    fixed_ = system.fixed;
    for (std::size_t j = 0; j < knots; ++j) {
        if (!positiveFinite(system.mass[j]))
            badSystem("knot " + std::to_string(j) + " has mass " + formatNumber(system.mass[j]) +
                      " kg; a knot mass must be finite and > 0");
        weight_[j] = system.gravity * system.mass[j];
        inverseWeight_[j] = 1.0 / (system.mass[j] * g);
    }

    bars_.resize(bars);
    std::vector<std::uint32_t> degree(knots, 0);
    for (std::size_t b = 0; b < bars; ++b) {
        const std::uint32_t a = system.barA[b], e = system.barB[b];
        if (a >= knots || e >= knots || a == e)
            badSystem("bar " + std::to_string(b) + " joins knots " + std::to_string(a) + " and " +
                      std::to_string(e) + "; expected two different knots below " +
                      std::to_string(knots));
        if (!positiveFinite(system.restLength[b]))
            badSystem("bar " + std::to_string(b) + " has rest length " +
                      formatNumber(system.restLength[b]) + " m; must be finite and > 0");
        if (!positiveFinite(system.kTension[b]))
            badSystem("bar " + std::to_string(b) + " has kTension " +
                      formatNumber(system.kTension[b]) + " N/m; must be finite and > 0");
        if (!std::isfinite(system.kCompression[b]) || system.kCompression[b] < 0)
            badSystem("bar " + std::to_string(b) + " has kCompression " +
                      formatNumber(system.kCompression[b]) + " N/m; must be finite and >= 0");
        bars_[b] = Bar{a, e, system.restLength[b], system.kTension[b], system.kCompression[b]};
        ++degree[a];
        ++degree[e];
    }

    // Knot -> bar table (CSR), bars in increasing index: the fixed order of the sum in Eq. 3.
    adjacencyStart_.assign(knots + 1, 0);
    for (std::size_t j = 0; j < knots; ++j) {
        if (!fixed_[j] && degree[j] == 0)
            badSystem("knot " + std::to_string(j) + " is free and has no bar");
        adjacencyStart_[j + 1] = adjacencyStart_[j] + degree[j];
    }
    adjacency_.resize(2 * bars);
    adjacentBars_.resize(2 * bars);
    std::vector<std::uint32_t> next(adjacencyStart_.begin(), adjacencyStart_.end() - 1);
    for (std::size_t b = 0; b < bars; ++b) {
        const auto bar = static_cast<std::uint32_t>(b);
        adjacency_[next[bars_[b].a]] = 2 * bar;
        adjacentBars_[next[bars_[b].a]++] = bar;
        adjacency_[next[bars_[b].b]] = 2 * bar + 1;
        adjacentBars_[next[bars_[b].b]++] = bar;
    }
    barForce_.resize(bars);
}

void ForceField::setLoad(const std::optional<Wind>& wind, double stiffnessScale) {
    if (!positiveFinite(stiffnessScale))
        throw UserError("stiffness scale must be finite and > 0, got " +
                        formatNumber(stiffnessScale));
    hasWind_ = false;
    if (wind) {
        windDirection_ = validatedWindDirection(*wind);
        windPressure_ = wind->pressure;
        hasWind_ = windPressure_ > 0;
        barWind_.resize(hasWind_ ? barCount() : 0);
    }
    scale_ = stiffnessScale;
}

std::span<const std::uint32_t> ForceField::barsOfKnot(std::size_t j) const {
    return {adjacentBars_.data() + adjacencyStart_[j],
            adjacentBars_.data() + adjacencyStart_[j + 1]};
}

void ForceField::computeBars(const Vec3* positions, std::size_t begin, std::size_t end,
                             double* tension) {
    const double scale = scale_;
    for (std::size_t b = begin; b < end; ++b) {
        const Bar& bar = bars_[b];
        const Vec3 d = positions[bar.b] - positions[bar.a];
        const double length = d.norm();
        const double extension = length - bar.restLength;
        const double k = (extension > 0 ? bar.kTension : bar.kCompression) * scale;
        const double t = k * extension; // N, < 0 in compression (Eq. 3)
        if (tension)
            tension[b] = t;
        // Force on end a: t along the unit vector from a to b (Eq. 3); end b gets the opposite.
        barForce_[b] = length > 0 ? d * (t / length) : Vec3{};
        if (hasWind_) {
            // q L times the part of the wind direction normal to the bar, half to each end.
            const Vec3 normal = windDirection_ - d * (windDirection_.dot(d) / (length * length));
            barWind_[b] = length > 0 ? normal * (0.5 * windPressure_ * length) : Vec3{};
        }
    }
}

void ForceField::evaluate(std::span<const Vec3> positions, std::span<Vec3> force,
                          ThreadPool* pool) {
    assert(positions.size() == knotCount() && force.size() == knotCount());
    auto bars = [&](std::size_t begin, std::size_t end, std::size_t) {
        computeBars(positions.data(), begin, end);
    };
    auto knots = [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t j = begin; j < end; ++j)
            force[j] = knotForce(j);
    };
    if (pool) {
        pool->parallelFor(barCount(), bars);
        pool->parallelFor(knotCount(), knots);
    } else {
        bars(0, barCount(), 0);
        knots(0, knotCount(), 0);
    }
}

double totalWeight(const MassSpringSystem& system) {
    const double g = system.gravity.norm();
    double total = 0;
    for (double m : system.mass)
        total += m * g;
    return total;
}

std::vector<Vec3> knotForces(const MassSpringSystem& system, const std::optional<Wind>& wind) {
    ForceField field(system);
    field.setLoad(wind, 1.0);
    std::vector<Vec3> force(system.knotCount());
    field.evaluate(system.position, force);
    return force;
}

std::vector<double> knotResiduals(const MassSpringSystem& system, const std::optional<Wind>& wind) {
    ForceField field(system);
    field.setLoad(wind, 1.0);
    std::vector<Vec3> force(system.knotCount());
    field.evaluate(system.position, force);
    std::vector<double> result(system.knotCount(), 0.0);
    for (std::size_t j = 0; j < result.size(); ++j)
        if (!field.isFixed(j))
            result[j] = field.residualOf(j, force[j]);
    return result;
}

double residual(const MassSpringSystem& system, const std::optional<Wind>& wind) {
    double worst = 0;
    for (double r : knotResiduals(system, wind)) {
        if (!std::isfinite(r))
            return std::numeric_limits<double>::infinity();
        worst = std::max(worst, r);
    }
    return worst;
}

std::vector<double> barTensions(const MassSpringSystem& system) {
    ForceField field(system);
    std::vector<double> tension(system.barCount());
    field.computeBars(system.position.data(), 0, system.barCount(), tension.data());
    return tension;
}

std::vector<Vec3> reactions(const MassSpringSystem& system, const std::optional<Wind>& wind) {
    std::vector<Vec3> result = knotForces(system, wind);
    for (std::size_t j = 0; j < result.size(); ++j)
        result[j] = system.fixed[j] ? -result[j] : Vec3{};
    return result;
}

} // namespace netsculpt
