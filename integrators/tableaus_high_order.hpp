#pragma once
// High-order explicit methods: the embedded pairs (one file each under
// integrators/methods/) and the tableaus they propagate with for the
// fixed-step ones (rkmk5, rkmk8).
#include "integrators/methods/bogacki_shampine32.hpp"
#include "integrators/methods/dormand_prince54.hpp"
#include "integrators/methods/dormand_prince853.hpp"
#include "integrators/methods/fehlberg78.hpp"

namespace rb {

namespace tableaus {

// The propagating methods of the pairs, for fixed-step runs. The 8th-order
// one is Fehlberg's (what odeint's runge_kutta_fehlberg78 advances with):
// DOP853's 8th-order weights at fixed step reach 1e-13 on valley-sideways by
// h = 1/16, still converging from above (omega like h^9), too soon for the
// registry's order test to see order 8.
inline Tableau dormand_prince5() { return pairs::dormand_prince54().tableau("dp5"); }
inline Tableau fehlberg8() { return pairs::fehlberg78().tableau("fehlberg8"); }

}  // namespace tableaus

}  // namespace rb
