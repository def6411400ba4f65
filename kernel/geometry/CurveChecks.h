#pragma once
// The checks a rail's CurveSpec passes before its curve is built (Curve.cpp), and their
// messages: each names the value and what is allowed, as a UserError "rail: ...".

#include "geometry/Curve.h"

#include <cstddef>
#include <string>

namespace netsculpt::curve_checks {

constexpr int kMaxDegree = 7;

[[noreturn]] void fail(const std::string& what);

std::string num(double value);
std::string num(std::size_t value);
std::string num(int value);
std::string num(const Vec3& p);

/// The number of control points the knot vector belongs to: closed splines wrap `degree` more.
std::size_t wrappedCount(const CurveSpec& spec);

void checkFinite(double value, const char* what);
void checkFiniteCoordinates(const CurveSpec& spec);
void checkPolylineSpec(const CurveSpec& spec);
/// Degree and control point count, weights, the knot vector if given, distinct points.
void checkSplineSpec(const CurveSpec& spec);
void checkLength(double length);

} // namespace netsculpt::curve_checks
