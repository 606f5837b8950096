#pragma once
// The components of a run's error against its reference, listed once: the
// sweep measures them in this order, the order fit fits each, and the report
// lists them under "error_components" for the analysis (docs/formats.md,
// "Top level").
#include <array>
#include <cstddef>

namespace rb {

// What a component is divided by to be dimensionless in "worst": the ball's
// radius, the reference's largest |omega| (omega_scale), or nothing.
enum class ErrorScale { radius, omega_scale, one };

struct ErrorComponent {
  const char* name;   // the key in a run's "error", "below_floor", an order's "observed"
  const char* label;  // what it measures, for axes and tables (the unit follows)
  const char* unit;
  ErrorScale scale;
};

inline constexpr std::array<ErrorComponent, 4> kErrorComponents{{
    {"contact", "contact-point error", "m", ErrorScale::radius},
    {"centre", "centre error", "m", ErrorScale::radius},
    {"omega", "angular-velocity error", "rad/s", ErrorScale::omega_scale},
    {"rotation", "rotation error", "rad", ErrorScale::one},
}};

inline constexpr std::size_t kErrorComponentCount = kErrorComponents.size();

// The component an order's "fit" and the summary table's order column show:
// the first, the contact point.
inline constexpr std::size_t kHeadlineComponent = 0;

// The scale's name in the report: "radius", "omega_scale" or "1".
inline const char* scale_name(ErrorScale s) {
  switch (s) {
    case ErrorScale::radius: return "radius";
    case ErrorScale::omega_scale: return "omega_scale";
    case ErrorScale::one: return "1";
  }
  return "1";
}

// The number a component is divided by, for a ball of this radius and a
// reference of this omega_scale.
inline double scale_value(ErrorScale s, double radius, double omega_scale) {
  switch (s) {
    case ErrorScale::radius: return radius;
    case ErrorScale::omega_scale: return omega_scale;
    case ErrorScale::one: return 1.0;
  }
  return 1.0;
}

}  // namespace rb
