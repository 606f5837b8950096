#pragma once
// High-order explicit methods: embedded pairs with their dense output for
// the adaptive Munthe-Kaas methods, and the tableaus they propagate with for
// the fixed-step ones (rkmk5, rkmk8). Tableau checks order conditions up to 4
// only; tests/integrators/test_lie_adaptive.cpp checks every rooted tree up to
// each method's order, and the dense outputs' continuous orders.
//
// Sources: Bogacki & Shampine (1989); Dormand & Prince (1980); DOP853 of
// Hairer, Norsett & Wanner, Solving ODEs I (coefficients as in its Fortran
// code, also used by SciPy), with its 7th-order dense output.
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "integrators/tableau.hpp"

namespace rb {

// An embedded explicit Runge-Kutta pair with a dense output. Stage i has node
// c[i] and row a[i][*] (row-major, total x total). Three groups of stages:
//   0 .. stages-1        evaluated in every attempt; b and e weight only these
//   fsal                 the stage at (t + h, y_new): its row of A equals b and
//                        c = 1, so its right-hand side starts the next step;
//                        fsal < stages when the error estimate uses it (BS32,
//                        DP54), fsal == stages when it is evaluated only after
//                        an accepted step (DP853; and F78, which has no FSAL
//                        stage but needs f(y_new) next all the same)
//   up to total-1        the extra stages only the dense output needs
struct EmbeddedPair {
  std::string name;
  int order = 0;        // of b, the solution that is propagated
  int error_order = 0;  // the local error estimate is O(h^error_order)
  int stages = 0;
  int fsal = 0;
  int total = 0;
  std::vector<double> a, c;
  std::vector<double> b;   // total entries, zero past the propagating stages
  std::vector<double> e;   // b - b_hat: h sum e_i k_i estimates the local error
  std::vector<double> e3;  // DP853's 3rd-order estimate b - b_hat3 (Hairer's "stretched" error); empty elsewhere
  int dense_order = 0;     // of the continuous extension; 0: none
  int dense_degree = 0;
  // b_i(theta) = sum_k dense[i * dense_degree + k] theta^(k + 1): the weights
  // of the step to t + theta h; b_i(1) = b_i.
  std::vector<double> dense;

  double a_at(int i, int j) const { return a[static_cast<std::size_t>(i * total + j)]; }
  // The propagating method alone as a fixed-step tableau: the stages up to
  // the last non-zero b.
  Tableau tableau(const std::string& tableau_name) const {
    int s = total;
    while (s > 0 && b[static_cast<std::size_t>(s - 1)] == 0.0) --s;
    std::vector<double> as(static_cast<std::size_t>(s * s));
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) as[static_cast<std::size_t>(i * s + j)] = a_at(i, j);
    return Tableau(tableau_name, order, as, {b.begin(), b.begin() + s}, {c.begin(), c.begin() + s});
  }
};

namespace pairs {

namespace detail {

struct Entry {
  int i, j;
  double value;
};

inline std::vector<double> matrix(int n, std::initializer_list<Entry> entries) {
  std::vector<double> m(static_cast<std::size_t>(n * n), 0.0);
  for (const Entry& x : entries) m[static_cast<std::size_t>(x.i * n + x.j)] = x.value;
  return m;
}

}  // namespace detail

// Bogacki-Shampine 3(2): FSAL, 3 new stages an attempt; the dense output is
// the cubic Hermite interpolant (3rd order) through both ends' derivatives.
inline EmbeddedPair bogacki_shampine32() {
  EmbeddedPair p;
  p.name = "bs32";
  p.order = 3;
  p.error_order = 3;
  p.stages = p.total = 4;
  p.fsal = 3;
  p.a = {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.75, 0, 0, 2.0 / 9, 1.0 / 3, 4.0 / 9, 0};
  p.c = {0, 0.5, 0.75, 1};
  p.b = {2.0 / 9, 1.0 / 3, 4.0 / 9, 0};
  p.e = {5.0 / 72, -1.0 / 12, -1.0 / 9, 1.0 / 8};
  p.dense_order = 3;
  p.dense_degree = 3;
  p.dense = {1, -4.0 / 3, 5.0 / 9, 0, 1, -2.0 / 3, 0, 4.0 / 3, -8.0 / 9, 0, -1, 1};
  return p;
}

// Dormand-Prince 5(4) (DOPRI5): FSAL, 6 new stages an attempt; Shampine's
// 4th-order dense output.
inline EmbeddedPair dormand_prince54() {
  EmbeddedPair p;
  p.name = "dp54";
  p.order = 5;
  p.error_order = 5;
  p.stages = p.total = 7;
  p.fsal = 6;
  p.a = detail::matrix(7, {{1, 0, 1.0 / 5},
                           {2, 0, 3.0 / 40}, {2, 1, 9.0 / 40},
                           {3, 0, 44.0 / 45}, {3, 1, -56.0 / 15}, {3, 2, 32.0 / 9},
                           {4, 0, 19372.0 / 6561}, {4, 1, -25360.0 / 2187}, {4, 2, 64448.0 / 6561},
                           {4, 3, -212.0 / 729},
                           {5, 0, 9017.0 / 3168}, {5, 1, -355.0 / 33}, {5, 2, 46732.0 / 5247}, {5, 3, 49.0 / 176},
                           {5, 4, -5103.0 / 18656},
                           {6, 0, 35.0 / 384}, {6, 2, 500.0 / 1113}, {6, 3, 125.0 / 192}, {6, 4, -2187.0 / 6784},
                           {6, 5, 11.0 / 84}});
  p.c = {0, 0.2, 0.3, 0.8, 8.0 / 9, 1, 1};
  p.b = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
  p.e = {-71.0 / 57600, 0, 71.0 / 16695, -71.0 / 1920, 17253.0 / 339200, -22.0 / 525, 1.0 / 40};
  p.dense_order = 4;
  p.dense_degree = 4;
  p.dense = {1, -8048581381.0 / 2820520608, 8663915743.0 / 2820520608, -12715105075.0 / 11282082432,
             0, 0, 0, 0,
             0, 131558114200.0 / 32700410799, -68118460800.0 / 10900136933, 87487479700.0 / 32700410799,
             0, -1754552775.0 / 470086768, 14199869525.0 / 1410260304, -10690763975.0 / 1880347072,
             0, 127303824393.0 / 49829197408, -318862633887.0 / 49829197408, 701980252875.0 / 199316789632,
             0, -282668133.0 / 205662961, 2019193451.0 / 616988883, -1453857185.0 / 822651844,
             0, 40617522.0 / 29380423, -110615467.0 / 29380423, 69997945.0 / 29380423};
  return p;
}

// Dormand-Prince 8(5,3) (DOP853): 12 stages an attempt, the FSAL stage after
// acceptance, 3 more for the 7th-order dense output (16 in all).
inline EmbeddedPair dormand_prince853() {
  EmbeddedPair p;
  p.name = "dp853";
  p.order = 8;
  p.error_order = 8;  // |err5|^2 / sqrt(|err5|^2 + 0.01 |err3|^2) behaves like h^8
  p.stages = 12;
  p.fsal = 12;
  p.total = 16;
  // clang-format off
  p.a = detail::matrix(16, {
    {1, 0, 5.26001519587677318785587544488e-2},
    {2, 0, 1.97250569845378994544595329183e-2}, {2, 1, 5.91751709536136983633785987549e-2},
    {3, 0, 2.95875854768068491816892993775e-2}, {3, 2, 8.87627564304205475450678981324e-2},
    {4, 0, 2.41365134159266685502369798665e-1}, {4, 2, -8.84549479328286085344864962717e-1},
    {4, 3, 9.24834003261792003115737966543e-1},
    {5, 0, 3.7037037037037037037037037037e-2}, {5, 3, 1.70828608729473871279604482173e-1},
    {5, 4, 1.25467687566822425016691814123e-1},
    {6, 0, 3.7109375e-2}, {6, 3, 1.70252211019544039314978060272e-1}, {6, 4, 6.02165389804559606850219397283e-2},
    {6, 5, -1.7578125e-2},
    {7, 0, 3.70920001185047927108779319836e-2}, {7, 3, 1.70383925712239993810214054705e-1},
    {7, 4, 1.07262030446373284651809199168e-1}, {7, 5, -1.53194377486244017527936158236e-2},
    {7, 6, 8.27378916381402288758473766002e-3},
    {8, 0, 6.24110958716075717114429577812e-1}, {8, 3, -3.36089262944694129406857109825},
    {8, 4, -8.68219346841726006818189891453e-1}, {8, 5, 2.75920996994467083049415600797e1},
    {8, 6, 2.01540675504778934086186788979e1}, {8, 7, -4.34898841810699588477366255144e1},
    {9, 0, 4.77662536438264365890433908527e-1}, {9, 3, -2.48811461997166764192642586468},
    {9, 4, -5.90290826836842996371446475743e-1}, {9, 5, 2.12300514481811942347288949897e1},
    {9, 6, 1.52792336328824235832596922938e1}, {9, 7, -3.32882109689848629194453265587e1},
    {9, 8, -2.03312017085086261358222928593e-2},
    {10, 0, -9.3714243008598732571704021658e-1}, {10, 3, 5.18637242884406370830023853209},
    {10, 4, 1.09143734899672957818500254654}, {10, 5, -8.14978701074692612513997267357},
    {10, 6, -1.85200656599969598641566180701e1}, {10, 7, 2.27394870993505042818970056734e1},
    {10, 8, 2.49360555267965238987089396762}, {10, 9, -3.0467644718982195003823669022},
    {11, 0, 2.27331014751653820792359768449}, {11, 3, -1.05344954667372501984066689879e1},
    {11, 4, -2.00087205822486249909675718444}, {11, 5, -1.79589318631187989172765950534e1},
    {11, 6, 2.79488845294199600508499808837e1}, {11, 7, -2.85899827713502369474065508674},
    {11, 8, -8.87285693353062954433549289258}, {11, 9, 1.23605671757943030647266201528e1},
    {11, 10, 6.43392746015763530355970484046e-1},
    {12, 0, 5.42937341165687622380535766363e-2}, {12, 5, 4.45031289275240888144113950566},
    {12, 6, 1.89151789931450038304281599044}, {12, 7, -5.8012039600105847814672114227},
    {12, 8, 3.1116436695781989440891606237e-1}, {12, 9, -1.52160949662516078556178806805e-1},
    {12, 10, 2.01365400804030348374776537501e-1}, {12, 11, 4.47106157277725905176885569043e-2},
    {13, 0, 5.61675022830479523392909219681e-2}, {13, 6, 2.53500210216624811088794765333e-1},
    {13, 7, -2.46239037470802489917441475441e-1}, {13, 8, -1.24191423263816360469010140626e-1},
    {13, 9, 1.5329179827876569731206322685e-1}, {13, 10, 8.20105229563468988491666602057e-3},
    {13, 11, 7.56789766054569976138603589584e-3}, {13, 12, -8.298e-3},
    {14, 0, 3.18346481635021405060768473261e-2}, {14, 5, 2.83009096723667755288322961402e-2},
    {14, 6, 5.35419883074385676223797384372e-2}, {14, 7, -5.49237485713909884646569340306e-2},
    {14, 10, -1.08347328697249322858509316994e-4}, {14, 11, 3.82571090835658412954920192323e-4},
    {14, 12, -3.40465008687404560802977114492e-4}, {14, 13, 1.41312443674632500278074618366e-1},
    {15, 0, -4.28896301583791923408573538692e-1}, {15, 5, -4.69762141536116384314449447206},
    {15, 6, 7.68342119606259904184240953878}, {15, 7, 4.06898981839711007970213554331},
    {15, 8, 3.56727187455281109270669543021e-1}, {15, 12, -1.39902416515901462129418009734e-3},
    {15, 13, 2.9475147891527723389556272149}, {15, 14, -9.15095847217987001081870187138}});
  p.c = {0.0, 0.526001519587677318785587544488e-01, 0.789002279381515978178381316732e-01,
         0.118350341907227396726757197510, 0.281649658092772603273242802490, 1.0 / 3, 0.25, 4.0 / 13,
         127.0 / 195, 0.6, 6.0 / 7, 1.0, 1.0, 0.1, 0.2, 7.0 / 9};
  // clang-format on
  p.b.assign(16, 0.0);
  for (int j = 0; j < 12; ++j) p.b[static_cast<std::size_t>(j)] = p.a_at(12, j);
  p.e.assign(16, 0.0);
  const detail::Entry e5[] = {{0, 0, 0.1312004499419488073250102996e-1}, {0, 5, -0.1225156446376204440720569753e+1},
                              {0, 6, -0.4957589496572501915214079952}, {0, 7, 0.1664377182454986536961530415e+1},
                              {0, 8, -0.3503288487499736816886487290}, {0, 9, 0.3341791187130174790297318841},
                              {0, 10, 0.8192320648511571246570742613e-1},
                              {0, 11, -0.2235530786388629525884427845e-1}};
  for (const detail::Entry& x : e5) p.e[static_cast<std::size_t>(x.j)] = x.value;
  p.e3 = p.b;
  p.e3[0] -= 0.244094488188976377952755905512;
  p.e3[8] -= 0.733846688281611857341361741547;
  p.e3[11] -= 0.220588235294117647058823529412e-1;

  // The dense output as Hairer writes it: y(theta) = y_n + theta (F0 +
  // (1-theta) (F1 + theta (F2 + (1-theta) (F3 + theta (F4 + (1-theta) (F5 +
  // theta F6)))))), each F_k = h sum_j f[k][j] k_j; expanded here to powers.
  // clang-format off
  const double d[4][16] = {
    {-0.84289382761090128651353491142e+1, 0, 0, 0, 0, 0.56671495351937776962531783590,
     -0.30689499459498916912797304727e+1, 0.23846676565120698287728149680e+1, 0.21170345824450282767155149946e+1,
     -0.87139158377797299206789907490, 0.22404374302607882758541771650e+1, 0.63157877876946881815570249290,
     -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e+2, -0.91946323924783554000451984436e+1,
     -0.44360363875948939664310572000e+1},
    {0.10427508642579134603413151009e+2, 0, 0, 0, 0, 0.24228349177525818288430175319e+3,
     0.16520045171727028198505394887e+3, -0.37454675472269020279518312152e+3, -0.22113666853125306036270938578e+2,
     0.77334326684722638389603898808e+1, -0.30674084731089398182061213626e+2, -0.93321305264302278729567221706e+1,
     0.15697238121770843886131091075e+2, -0.31139403219565177677282850411e+2, -0.93529243588444783865713862664e+1,
     0.35816841486394083752465898540e+2},
    {0.19985053242002433820987653617e+2, 0, 0, 0, 0, -0.38703730874935176555105901742e+3,
     -0.18917813819516756882830838328e+3, 0.52780815920542364900561016686e+3, -0.11573902539959630126141871134e+2,
     0.68812326946963000169666922661e+1, -0.10006050966910838403183860980e+1, 0.77771377980534432092869265740,
     -0.27782057523535084065932004339e+1, -0.60196695231264120758267380846e+2, 0.84320405506677161018159903784e+2,
     0.11992291136182789328035130030e+2},
    {-0.25693933462703749003312586129e+2, 0, 0, 0, 0, -0.15418974869023643374053993627e+3,
     -0.23152937917604549567536039109e+3, 0.35763911791061412378285349910e+3, 0.93405324183624310003907691704e+2,
     -0.37458323136451633156875139351e+2, 0.10409964950896230045147246184e+3, 0.29840293426660503123344363579e+2,
     -0.43533456590011143754432175058e+2, 0.96324553959188282948394950600e+2, -0.39177261675615439165231486172e+2,
     -0.14972683625798562581422125276e+3}};
  // clang-format on
  p.dense_order = 7;
  p.dense_degree = 7;
  p.dense.assign(16 * 7, 0.0);
  // F_k's factor w_k(theta) is theta, theta (1-theta), theta^2 (1-theta), ...:
  // each is the one before times (1-theta) or theta, alternately
  std::vector<double> w = {0, 1};  // coefficients of theta^0, theta^1, ...
  for (int k = 0; k < 7; ++k) {
    for (int j = 0; j < 16; ++j) {
      const std::size_t uj = static_cast<std::size_t>(j);
      const double f = k == 0   ? p.b[uj]
                       : k == 1 ? (j == 0) - p.b[uj]
                       : k == 2 ? 2 * p.b[uj] - (j == 0) - (j == 12)
                                : d[k - 3][j];
      for (std::size_t m = 1; m < w.size(); ++m) p.dense[uj * 7 + m - 1] += f * w[m];
    }
    // next basis: times (1 - theta) after an even k, times theta after an odd k
    std::vector<double> next(w.size() + 1, 0.0);
    for (std::size_t m = 0; m < w.size(); ++m) {
      if (k % 2 == 0) {
        next[m] += w[m];
        next[m + 1] -= w[m];
      } else {
        next[m + 1] += w[m];
      }
    }
    w = std::move(next);
  }
  return p;
}

// Fehlberg 7(8) as Boost.Odeint's runge_kutta_fehlberg78: 13 stages, no
// FSAL (its first stage is evaluated after acceptance), advances with the
// 8th-order solution; the estimate is the 7th-order one's error, O(h^8). No
// dense output: steps land on the outputs.
inline EmbeddedPair fehlberg78() {
  EmbeddedPair p;
  p.name = "f78";
  p.order = 8;
  p.error_order = 8;
  p.stages = p.fsal = p.total = 13;
  // clang-format off
  p.a = detail::matrix(13, {
    {1, 0, 2.0 / 27},
    {2, 0, 1.0 / 36}, {2, 1, 1.0 / 12},
    {3, 0, 1.0 / 24}, {3, 2, 1.0 / 8},
    {4, 0, 5.0 / 12}, {4, 2, -25.0 / 16}, {4, 3, 25.0 / 16},
    {5, 0, 1.0 / 20}, {5, 3, 1.0 / 4}, {5, 4, 1.0 / 5},
    {6, 0, -25.0 / 108}, {6, 3, 125.0 / 108}, {6, 4, -65.0 / 27}, {6, 5, 125.0 / 54},
    {7, 0, 31.0 / 300}, {7, 4, 61.0 / 225}, {7, 5, -2.0 / 9}, {7, 6, 13.0 / 900},
    {8, 0, 2.0}, {8, 3, -53.0 / 6}, {8, 4, 704.0 / 45}, {8, 5, -107.0 / 9}, {8, 6, 67.0 / 90}, {8, 7, 3.0},
    {9, 0, -91.0 / 108}, {9, 3, 23.0 / 108}, {9, 4, -976.0 / 135}, {9, 5, 311.0 / 54}, {9, 6, -19.0 / 60},
    {9, 7, 17.0 / 6}, {9, 8, -1.0 / 12},
    {10, 0, 2383.0 / 4100}, {10, 3, -341.0 / 164}, {10, 4, 4496.0 / 1025}, {10, 5, -301.0 / 82},
    {10, 6, 2133.0 / 4100}, {10, 7, 45.0 / 82}, {10, 8, 45.0 / 164}, {10, 9, 18.0 / 41},
    {11, 0, 3.0 / 205}, {11, 5, -6.0 / 41}, {11, 6, -3.0 / 205}, {11, 7, -3.0 / 41}, {11, 8, 3.0 / 41},
    {11, 9, 6.0 / 41},
    {12, 0, -1777.0 / 4100}, {12, 3, -341.0 / 164}, {12, 4, 4496.0 / 1025}, {12, 5, -289.0 / 82},
    {12, 6, 2193.0 / 4100}, {12, 7, 51.0 / 82}, {12, 8, 33.0 / 164}, {12, 9, 12.0 / 41}, {12, 11, 1.0}});
  p.c = {0, 2.0 / 27, 1.0 / 9, 1.0 / 6, 5.0 / 12, 0.5, 5.0 / 6, 1.0 / 6, 2.0 / 3, 1.0 / 3, 1, 0, 1};
  p.b = {0, 0, 0, 0, 0, 34.0 / 105, 9.0 / 35, 9.0 / 35, 9.0 / 280, 9.0 / 280, 0, 41.0 / 840, 41.0 / 840};
  // clang-format on
  const double q = 41.0 / 840;
  p.e = {-q, 0, 0, 0, 0, 0, 0, 0, 0, 0, -q, q, q};
  return p;
}

}  // namespace pairs

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
