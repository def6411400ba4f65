// Enter in an inspector field: the shown, rounded text read back is not an edit; a number typed
// is.

#include "TypedValue.h"

#include <catch2/catch.hpp>

#include <limits>

using netsculpt::studio::isEdit;

TEST_CASE("typed value: Enter on a field showing a rounded value leaves the value as it is",
          "[studio]") {
    // What the field shows with "%.4g", read back.
    CHECK_FALSE(isEdit(0.23456, 0.2346, "%.4g"));     // a bar length from a script
    CHECK_FALSE(isEdit(123456.0, 123500.0, "%.4g"));  // EA shown as 1.235e+05
    CHECK_FALSE(isEdit(0.0012347, 0.001235, "%.4g")); // a knot mass
    CHECK_FALSE(isEdit(0.25, 0.25, "%.4g"));
}

TEST_CASE("typed value: a number typed is an edit, a number not finite is not", "[studio]") {
    CHECK(isEdit(0.23456, 0.235, "%.4g"));
    CHECK(isEdit(0.25, 0.26, "%.4g"));
    CHECK(isEdit(0.23456, 0.23456001, "%.4g")); // finer than the field shows: still typed
    CHECK_FALSE(isEdit(0.25, std::numeric_limits<double>::infinity(), "%.4g"));
    CHECK_FALSE(isEdit(0.25, std::numeric_limits<double>::quiet_NaN(), "%.4g"));
}
