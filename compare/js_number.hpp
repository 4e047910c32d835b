// JavaScript's number formatting, to the digit, for Resemble.js-identical output.
#pragma once

#include <string>

namespace aosuite {

// Number.prototype.toFixed(2): decided by the exact binary value; an exact tie rounds up
// (3.125 -> "3.13", where printf gives "3.12"). Valid for |x| < 1e21.
std::string js_to_fixed2(double x);

// Number.prototype.toString(): the shortest digits that round-trip, laid out as ECMAScript's
// Number::toString does (1e21 and 1e-7 switch to exponent form, "NaN", "Infinity").
std::string js_number_to_string(double x);

}  // namespace aosuite
