// Enter in an inspector field: the shown, rounded text read back is not an edit; a number typed
// is. An optional number's field (a breaking load): blank is none, a word is an error.

#include "TypedValue.h"

#include <catch2/catch.hpp>

#include <limits>

using netsculpt::studio::isEdit;
using netsculpt::studio::readOptional;

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

TEST_CASE("typed value: an optional number's field is blank for none, and a word is an error",
          "[studio]") {
    // A breaking load of 2345.678 N shows as 2346 with "%.4g".
    CHECK_FALSE(readOptional("2346", 2345.678, "%.4g").edit); // Enter on it untouched
    const auto typed = readOptional(" 3000 ", 2345.678, "%.4g");
    CHECK(typed.edit);
    CHECK(typed.value == 3000);
    CHECK(readOptional("3000", std::nullopt, "%.4g").value == 3000); // none before
    // Cleared: none, an edit only when there was one.
    const auto cleared = readOptional("  ", 2345.678, "%.4g");
    CHECK(cleared.edit);
    CHECK_FALSE(cleared.value.has_value());
    CHECK_FALSE(readOptional("", std::nullopt, "%.4g").edit);
    // 0, negative and infinite numbers are edits, for the command to refuse with what is allowed.
    CHECK(readOptional("0", 2345.678, "%.4g").value == 0);
    CHECK(readOptional("-5", 2345.678, "%.4g").edit);
    CHECK(readOptional("inf", 2345.678, "%.4g").edit);
    // Not a number: nothing is done, and the error says what was typed.
    const auto word = readOptional("strong", 2345.678, "%.4g");
    CHECK_FALSE(word.edit);
    CHECK(word.error == "\"strong\" is not a number (leave the field blank for none)");
    CHECK_FALSE(readOptional("3000 N", std::nullopt, "%.4g").edit);
}
