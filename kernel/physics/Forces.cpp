#include "physics/Forces.h"

#include "model/Error.h"
#include "physics/SpringForces.h"
#include "physics/ThreadPool.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace netsculpt {

using namespace springs;

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
    // Bars keep their ends as 32-bit byte offsets into the positions (24 bytes per knot).
    if (knots >= std::numeric_limits<std::uint32_t>::max() / sizeof(Vec3) ||
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

namespace {

/// The wind's whole load on a bar d = p_b - p_a (its ends take half each): q L times the part of
/// the unit wind direction normal to the bar; none on a bar of length 0.
Vec3 windOnBar(const Vec3& direction, double pressure, const Vec3& d) {
    const double length = std::sqrt(squaredLength(d));
    if (!(length > 0)) return {};
    return (direction - d * (direction.dot(d) / (length * length))) * (pressure * length);
}

/// |g| of `system`, validated.
double gravityOf(const MassSpringSystem& system) {
    const double g = system.gravity.norm();
    if (!system.gravity.isFinite() || !(g > 0))
        badSystem("gravity must be finite and non-zero, got |g| = " + formatNumber(g));
    return g;
}

void checkMass(const MassSpringSystem& system, std::size_t j) {
    if (!positiveFinite(system.mass[j]))
        badSystem("knot " + std::to_string(j) + " has mass " + formatNumber(system.mass[j]) +
                  " kg; a knot mass must be finite and > 0");
}

/// Bar b's rest length and stiffnesses.
void checkBarLaw(const MassSpringSystem& system, std::size_t b) {
    if (!positiveFinite(system.restLength[b]))
        badSystem("bar " + std::to_string(b) + " has rest length " +
                  formatNumber(system.restLength[b]) + " m; must be finite and > 0");
    if (!positiveFinite(system.kTension[b]))
        badSystem("bar " + std::to_string(b) + " has kTension " +
                  formatNumber(system.kTension[b]) + " N/m; must be finite and > 0");
    if (!std::isfinite(system.kCompression[b]) || system.kCompression[b] < 0)
        badSystem("bar " + std::to_string(b) + " has kCompression " +
                  formatNumber(system.kCompression[b]) + " N/m; must be finite and >= 0");
}

} // namespace

ForceField::ForceField(const MassSpringSystem& system) {
    checkSizes(system);
    const std::size_t knots = system.knotCount(), bars = system.barCount();
    const double g = gravityOf(system);

    weight_.resize(knots);
    inverseWeight_.resize(knots);
    fixed_ = system.fixed;
    for (std::size_t j = 0; j < knots; ++j) {
        checkMass(system, j);
        weight_[j] = system.gravity * system.mass[j];
        inverseWeight_[j] = 1.0 / (system.mass[j] * g);
    }

    endOffsets_.resize(2 * bars);
    restLength_ = system.restLength;
    kTension_ = system.kTension;
    kCompression_ = system.kCompression;
    std::vector<std::uint32_t> degree(knots, 0);
    for (std::size_t b = 0; b < bars; ++b) {
        const std::uint32_t a = system.barA[b], e = system.barB[b];
        if (a >= knots || e >= knots || a == e)
            badSystem("bar " + std::to_string(b) + " joins knots " + std::to_string(a) + " and " +
                      std::to_string(e) + "; expected two different knots below " +
                      std::to_string(knots));
        checkBarLaw(system, b);
        endOffsets_[2 * b] = a * std::uint32_t{sizeof(Vec3)};
        endOffsets_[2 * b + 1] = e * std::uint32_t{sizeof(Vec3)};
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
        adjacency_[next[system.barA[b]]] = 2 * bar;
        adjacentBars_[next[system.barA[b]]++] = bar;
        adjacency_[next[system.barB[b]]] = 2 * bar + 1;
        adjacentBars_[next[system.barB[b]]++] = bar;
    }
    barForce_.resize(bars);

    // Bounds of the streaming pass. A knot's bars lie between its first and its last bar (the
    // first and last entries of its row of the table); a knot without bars has none to walk.
    const auto noBar = static_cast<std::uint32_t>(bars);
    firstBarFrom_.assign(knots + 1, noBar);
    for (std::size_t j = knots; j-- > 0;) {
        const std::uint32_t first = degree[j] > 0 ? adjacentBars_[adjacencyStart_[j]] : noBar;
        firstBarFrom_[j] = std::min(firstBarFrom_[j + 1], first);
    }
    lastBarTo_.assign(knots, 0);
    for (std::size_t j = 0; j < knots; ++j) {
        const std::uint32_t last =
            degree[j] > 0 ? adjacentBars_[adjacencyStart_[j + 1] - 1] + 1 : 0;
        lastBarTo_[j] = std::max(j > 0 ? lastBarTo_[j - 1] : 0u, last);
    }
    unmaskedEnd_ = knots > 0 ? firstBarFrom_[knots - 1] : bars; // bars before: not at the last knot
    knotsBelow_.resize(bars);
    std::uint32_t largest = 0;
    for (std::size_t b = 0; b < bars; ++b) {
        largest = std::max({largest, system.barA[b] + 1, system.barB[b] + 1});
        knotsBelow_[b] = largest;
    }
}

void ForceField::setLaw(const MassSpringSystem& system) {
    checkSizes(system);
    const std::size_t knots = system.knotCount(), bars = system.barCount();
    assert(knots == knotCount() && bars == barCount());
    const double g = gravityOf(system);
    for (std::size_t j = 0; j < knots; ++j)
        checkMass(system, j);
    for (std::size_t b = 0; b < bars; ++b)
        checkBarLaw(system, b);
    // Validated: the field changes only now (a refused law leaves the previous one).
    for (std::size_t j = 0; j < knots; ++j) {
        weight_[j] = system.gravity * system.mass[j];
        inverseWeight_[j] = 1.0 / (system.mass[j] * g);
    }
    std::copy(system.restLength.begin(), system.restLength.end(), restLength_.begin());
    std::copy(system.kTension.begin(), system.kTension.end(), kTension_.begin());
    std::copy(system.kCompression.begin(), system.kCompression.end(), kCompression_.begin());
}

void ForceField::setCompressionStiffness(std::span<const double> kCompression) {
    assert(kCompression.size() == barCount());
    std::copy(kCompression.begin(), kCompression.end(), kCompression_.begin());
}

void ForceField::setLoad(const std::optional<Wind>& wind, double stiffnessScale) {
    if (!positiveFinite(stiffnessScale))
        throw UserError("stiffness scale must be finite and > 0, got " +
                        formatNumber(stiffnessScale));
    hasWind_ = false;
    windFrozen_ = false;
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
    const std::uint32_t* const ends = endOffsets_.data();
    std::size_t b = begin;
#if defined(__AVX2__)
    const __m256d scale = _mm256_set1_pd(scale_);
    for (; b + 4 <= end; b += 4) {
        const SpringForces4 f = b + 4 <= unmaskedEnd_
                                    ? springForces4<false>(positions, ends + 2 * b, &restLength_[b],
                                                           &kTension_[b], &kCompression_[b], scale)
                                    : springForces4<true>(positions, ends + 2 * b, &restLength_[b],
                                                          &kTension_[b], &kCompression_[b], scale);
        for (std::size_t i = 0; i < 4; ++i) {
            _mm_storeu_pd(&barForce_[b + i].x, f.xy[i]);
            _mm_store_sd(&barForce_[b + i].z, f.z[i]);
        }
        if (tension)
            _mm256_storeu_pd(tension + b, f.tension);
    }
#endif
    for (; b < end; ++b) {
        const SpringForce f =
            springForce(at(positions, ends[2 * b]), at(positions, ends[2 * b + 1]), restLength_[b],
                        kTension_[b], kCompression_[b], scale_);
        barForce_[b] = f.force;
        if (tension)
            tension[b] = f.tension;
    }
    if (hasWind_ && !windFrozen_)
        computeWind(positions, begin, end);
}

void ForceField::computeWind(const Vec3* positions, std::size_t begin, std::size_t end) {
    const std::uint32_t* const ends = endOffsets_.data();
    for (std::size_t b = begin; b < end; ++b) {
        const Vec3 d = at(positions, ends[2 * b + 1]) - at(positions, ends[2 * b]);
        barWind_[b] = windOnBar(windDirection_, windPressure_, d) * 0.5; // half to each end
    }
}

void ForceField::windChange(std::span<const Vec3> positions, std::span<const Vec3> move,
                            std::span<Vec3> out) const {
    std::fill(out.begin(), out.end(), Vec3{});
    if (!hasWind_)
        return;
    const Vec3& w = windDirection_;
    for (std::size_t b = 0; b < barCount(); ++b) {
        const std::uint32_t a = barEndA(b), e = barEndB(b);
        const Vec3 d = positions[e] - positions[a];
        const double length = d.norm();
        if (!(length > 0))
            continue;
        // The bar's load q L (w - (w.u) u) changes with its vector by
        // q [w u^T - u w^T - (w.u) (I - u u^T)]; half of it goes to each end.
        const Vec3 u = d / length, dv = move[e] - move[a];
        const double wu = w.dot(u), udv = u.dot(dv);
        const Vec3 change =
            (w * udv - u * w.dot(dv) - (dv - u * udv) * wu) * (0.5 * windPressure_);
        out[a] += change;
        out[e] += change;
    }
}

void ForceField::freezeWind(std::span<const Vec3> positions) {
    assert(positions.size() == knotCount());
    if (!hasWind_)
        return;
    computeWind(positions.data(), 0, barCount());
    windFrozen_ = true;
}

std::pair<std::size_t, std::size_t> ForceField::streamBarRange(std::size_t begin,
                                                               std::size_t end) const {
    const std::size_t first = firstBarFrom_[begin], last = lastBarTo_[end - 1];
    return {first, std::max(first, last)};
}

template <bool Checked>
void ForceField::streamBars(const Vec3* positions, Vec3* force, std::size_t begin, std::size_t end,
                            std::size_t firstKnot, std::size_t endKnot,
                            std::size_t* nextKnot) const {
    // Local copies: the compiler cannot know that the stores to force leave these alone.
    const Vec3* const weight = weight_.data();
    const std::uint32_t* const ends = endOffsets_.data();
    const std::uint32_t* const knotsBelow = knotsBelow_.data();
    const double* const restLength = restLength_.data();
    const double* const kTension = kTension_.data();
    const double* const kCompression = kCompression_.data();
    std::size_t j = *nextKnot;
    // Every knot that bars up to b can reach gets its weight before their forces are added.
    auto startKnots = [&](std::size_t b) {
        for (const std::size_t below = std::min<std::size_t>(knotsBelow[b], endKnot); j < below;
             ++j)
            force[j] = weight[j];
    };
    // Is the knot at this byte offset one of [firstKnot, endKnot)?
    const std::uint32_t firstOffset = static_cast<std::uint32_t>(firstKnot * sizeof(Vec3));
    const std::uint32_t offsetSpan =
        static_cast<std::uint32_t>((endKnot - firstKnot) * sizeof(Vec3));
    auto mine = [&](std::uint32_t offset) { return !Checked || offset - firstOffset < offsetSpan; };
    std::size_t b = begin;
#if defined(__AVX2__)
    // Eight or four bars at a time, added to their knots right away: the additions of one group
    // then overlap the square roots and divisions of the next (computing many groups ahead is
    // slower).
    auto addGroup = [&](const auto& f, std::size_t first, std::size_t width) {
        startKnots(first + width - 1);
        for (std::size_t i = 0; i < width; ++i) {
            const std::uint32_t ea = ends[2 * (first + i)], eb = ends[2 * (first + i) + 1];
            if (mine(ea))
                addTo(at(force, ea), f.xy[i], f.z[i]);
            if (mine(eb))
                subtractFrom(at(force, eb), f.xy[i], f.z[i]);
        }
    };
    // Groups of `width` bars while they last; `forces(masked)` computes the group at b.
    const std::size_t unmaskedEnd = unmaskedEnd_;
    auto groupsOf = [&](std::size_t width, const auto& forces) {
        for (; b + width <= end; b += width)
            addGroup(b + width <= unmaskedEnd ? forces(std::false_type{})
                                              : forces(std::true_type{}),
                     b, width);
    };
#if defined(__AVX512F__) && defined(__FMA__)
    const __m512d scale8 = _mm512_set1_pd(scale_);
    groupsOf(8, [&](auto masked) {
        return springForces8<masked()>(positions, ends + 2 * b, restLength + b, kTension + b,
                                       kCompression + b, scale8);
    });
#endif
    const __m256d scale = _mm256_set1_pd(scale_);
    groupsOf(4, [&](auto masked) {
        return springForces4<masked()>(positions, ends + 2 * b, restLength + b, kTension + b,
                                       kCompression + b, scale);
    });
#endif
    for (; b < end; ++b) {
        startKnots(b);
        const std::uint32_t ea = ends[2 * b], eb = ends[2 * b + 1];
        const Vec3 f = springForce(at(positions, ea), at(positions, eb), restLength[b], kTension[b],
                                   kCompression[b], scale_)
                           .force;
        if (mine(ea))
            addTo(at(force, ea), f);
        if (mine(eb))
            subtractFrom(at(force, eb), f);
    }
    *nextKnot = j;
}

void ForceField::streamKnots(const Vec3* positions, Vec3* force, std::size_t begin,
                             std::size_t end) const {
    const auto [first, last] = streamBarRange(begin, end);
    // Bars from `inner` on touch no knot before `begin`; bars before `outer` none from `end` on.
    const std::size_t inner =
        std::clamp<std::size_t>(begin > 0 ? lastBarTo_[begin - 1] : 0, first, last);
    const std::size_t outer = std::clamp<std::size_t>(firstBarFrom_[end], inner, last);
    std::size_t next = begin;
    streamBars<true>(positions, force, first, inner, begin, end, &next);
    streamBars<false>(positions, force, inner, outer, begin, end, &next);
    streamBars<true>(positions, force, outer, last, begin, end, &next);
    for (; next < end; ++next) // knots after the last bar's ends, and knots without bars
        force[next] = weight_[next];
}

void ForceField::evaluate(std::span<const Vec3> positions, std::span<Vec3> force,
                          ThreadPool* pool) {
    assert(positions.size() == knotCount() && force.size() == knotCount());
    const std::size_t knots = knotCount();
    bool stream = !hasWind_;
    if (stream && pool && pool->threadsNow() > 1) {
        // A thread walks the bars from the first to the last of its knots. Where knots far apart
        // in number share bars (pieces joined, numbered apart), the threads' walks overlap; past
        // a quarter more bars than there are, the two-phase way (each bar once) is faster.
        const std::size_t chunks = pool->chunkCount(knots);
        std::size_t walked = 0;
        for (std::size_t c = 0; c < chunks; ++c) {
            const auto [first, last] = streamBarRange(knots * c / chunks, knots * (c + 1) / chunks);
            walked += last - first;
        }
        stream = walked <= barCount() + barCount() / 4;
    }
    if (stream) {
        auto knotRange = [&](std::size_t begin, std::size_t end, std::size_t) {
            streamKnots(positions.data(), force.data(), begin, end);
        };
        if (pool)
            pool->parallelFor(knots, knotRange);
        else if (knots > 0)
            knotRange(0, knots, 0);
        return;
    }
    auto bars = [&](std::size_t begin, std::size_t end, std::size_t) {
        computeBars(positions.data(), begin, end);
    };
    auto knotForces = [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t j = begin; j < end; ++j)
            force[j] = knotForce(j);
    };
    if (pool) {
        pool->parallelFor(barCount(), bars);
        pool->parallelFor(knots, knotForces);
    } else {
        bars(0, barCount(), 0);
        knotForces(0, knots, 0);
    }
}

double ForceField::maxResidual(std::span<const Vec3> force) const {
    double worst = 0;
    for (std::size_t j = 0; j < knotCount(); ++j) {
        if (fixed_[j])
            continue;
        const double r = residualOf(j, force[j]);
        if (!std::isfinite(r))
            return std::numeric_limits<double>::infinity();
        worst = std::max(worst, r);
    }
    return worst;
}

double totalWeight(const MassSpringSystem& system) {
    const double g = system.gravity.norm();
    double total = 0;
    for (double m : system.mass)
        total += m * g;
    return total;
}

Vec3 totalWindForce(const MassSpringSystem& system, const Wind& wind) {
    const Vec3 direction = validatedWindDirection(wind);
    Vec3 total;
    for (std::size_t b = 0; b < system.barCount(); ++b)
        total += windOnBar(direction, wind.pressure,
                           system.position[system.barB[b]] - system.position[system.barA[b]]);
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

std::int64_t knotWithLargestResidual(const MassSpringSystem& system,
                                     const std::optional<Wind>& wind) {
    const std::vector<double> residuals = knotResiduals(system, wind);
    std::int64_t worst = -1;
    double largest = -1;
    for (std::size_t j = 0; j < residuals.size(); ++j) {
        if (system.fixed[j])
            continue;
        const double r = std::isfinite(residuals[j]) ? residuals[j]
                                                     : std::numeric_limits<double>::infinity();
        if (r > largest) {
            largest = r;
            worst = static_cast<std::int64_t>(j);
        }
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
