// Transcribed from reference/chapter5-kinematic-constraints.txt (C. Felippa, "PMP Dynamical
// Systems: Kinematic Constraints"), equation by equation. Values are as printed, errors included;
// H(t) entries are given by their amplitude (every load is a step at t = 0).
#include "validation/references/chapter_printed.hpp"

namespace condyn {

namespace {

using Q = ChapterQuantity;

// 6 x 3 blocks of eqs. 5.6 and 5.10 (columns ux2, ux3, uy3 after striking columns 1, 2, 4).
const std::vector<double> kStruckK = {-10, -10, -10, 0, -10, -10, 10, 0,   0,
                                      0,   0,   -5,  0, 10,  10,  0,  -10, 15};
const std::vector<double> kStruckM = {0, 0, 0, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 4};
const std::vector<double> kReducedK57 = {10, 0, 0, 0, 10, 10, 0, -10, 15};
const std::vector<double> kRecoveryK58 = {-10, -10, -10, 0, -10, -10, 0, 0, -5};

}  // namespace

const std::vector<PrintedCase>& chapter_printed() {
  static const std::vector<PrintedCase> cases = {
      {"chapter_5_5_1",
       "§5.5.1",
       {
           {"5.6", "M with columns 1, 2, 4 struck", Q::struck_mass, 6, 3, kStruckM, true},
           {"5.6", "K with columns 1, 2, 4 struck", Q::struck_stiffness, 6, 3, kStruckK},
           {"5.7", "reduced mass M_rr", Q::reduced_mass, 3, 3, {3, 0, 0, 0, 4, 0, 0, 0, 4}, true},
           {"5.7", "reduced stiffness K_rr", Q::reduced_stiffness, 3, 3, kReducedK57},
           {"5.7", "reduced load amplitudes", Q::reduced_loads, 3, 1, {0, 2, 1}},
           {"5.8", "reaction recovery K_sr", Q::recovery_stiffness, 3, 3, kRecoveryK58},
       }},
      {"chapter_5_5_2",
       "§5.5.2",
       {
           {"5.10", "K with columns 1, 2, 4 struck", Q::struck_stiffness, 6, 3, kStruckK},
           {"5.10",
            "f_tra: coefficients of (gx1, gy1, gy2)",
            Q::transfer_g,
            6,
            3,
            {-20, -10, 0, -10, -10, 0, 10, 0, 0, 0, 0, -5, 10, 10, 0, 10, 10, 5}},
           {"5.10",
            "f_tra: coefficients of (gx1'', gy1'', gy2'')",
            Q::transfer_gdd,
            6,
            3,
            {-5, 0, 0, 0, -5, 0, 0, 0, 0, 0, 0, -3, 0, 0, 0, 0, 0, 0},
            true},
           {"5.11", "reduced stiffness", Q::reduced_stiffness, 3, 3, kReducedK57},
           {"5.11",
            "reduced RHS: coefficients of (gx1, gy1, gy2)",
            Q::reduced_transfer_g,
            3,
            3,
            {10, 0, 0, 10, 10, 0, 10, 10, 5}},
           {"5.11",
            "reduced RHS: coefficients of g''",
            Q::reduced_transfer_gdd,
            3,
            3,
            {0, 0, 0, 0, 0, 0, 0, 0, 0},
            true},
           {"5.11", "reduced load amplitudes", Q::reduced_loads, 3, 1, {0, 2, 1}},
           {"5.12", "reaction recovery K_sr", Q::recovery_stiffness, 3, 3, kRecoveryK58},
           {"5.12",
            "reaction recovery: coefficients of g",
            Q::recovery_g,
            3,
            3,
            {20, 10, 0, 10, 10, 0, 0, 0, 5}},
           {"5.12",
            "reaction recovery: coefficients of g''",
            Q::recovery_gdd,
            3,
            3,
            {5, 0, 0, 0, 5, 0, 0, 0, 3},
            true},
       }},
      {"chapter_5_5_3", "§5.5.3", {}},
      {"chapter_5_6_1",
       "§5.6.1",
       {
           {"5.17",
            "master-slave transformation T",
            Q::transform,
            6,
            3,
            {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1}},
           {"5.21", "M̂ = TᵀMT", Q::reduced_mass, 3, 3, {8, 0, 0, 0, 6, 0, 0, 0, 10}, true},
           {"5.21", "K̂ = TᵀKT", Q::reduced_stiffness, 3, 3, {10, 10, 0, -10, 15, 5, 0, 5, 5}},
           {"5.21", "f̂ = Tᵀf (amplitudes)", Q::reduced_loads, 3, 1, {0, 0, 2}},
       }},
      {"chapter_5_6_2",
       "§5.6.2",
       {
           {"5.28",
            "f̂: coefficients of (g1, g2, g3)",
            Q::reduced_transfer_g,
            3,
            3,
            {0, 0, 0, 0, -5, 5, 0, -5, 5}},
           {"5.28",
            "f̂: coefficients of (g1'', g2'', g3'')",
            Q::reduced_transfer_gdd,
            3,
            3,
            {4, 0, 0, 0, -3, 0, 0, 0, 5},
            true},
           {"5.28", "f̂: load amplitudes", Q::reduced_loads, 3, 1, {0, 0, 1}},
       }},
  };
  return cases;
}

const std::vector<PrintedIntegral>& chapter_eq_5_14() {
  static const std::vector<PrintedIntegral> integrals = {
      {"ux1", {0, 1, 0.5}},  // ux1 = t + t²/2 + Cx1
      {"ux1", {0, 0, 1}},    // printed "ux1 = t² + Cy1"
      {"uy2", {0, 0, 0, -1}},
  };
  return integrals;
}

}  // namespace condyn
