// The balanced plain weave of cases/cells/plain-weave.toml (two warp yarns
// along x, two weft yarns along y, elliptic sections swept along sinusoids)
// homogenized with composite voxels: the symmetries of the weave and the
// Voigt/Reuss bounds, both known without the solver.

#include "oracles.hpp"

#include "homogenize/library_entry.hpp"
#include "micro/cell.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/unit_cell.hpp"

#include <string>

namespace lamina::test {
namespace {

// Symmetries of the weave (continuous and on the grid, n1 = n2 and every
// centre on a quarter of the cell): the map (x, y, z) -> (y, x, Lz - z)
// takes warp 0 to weft 0, warp 1 to weft 1 and back (a sin(2 pi x / L) at
// y = L/4 becomes a sin(2 pi y / L) at x = L/4, flipped in z to weft 0's
// -a sin(2 pi y / L)); so C11 = C22, C13 = C23, C55 = C66 (yz <-> xz).
// The mirror x -> -x followed by the shift y -> y + L/2 maps warp 0 <-> warp
// 1 and weft 0 <-> weft 1, so every constant with an odd number of x indices
// vanishes (likewise y): C is orthotropic. The grid voxels and their 10^3
// sub-samples map onto themselves; what breaks the symmetry is the solver's
// tolerance (1e-8: relative error of C ~ tol x contrast 11, 1e-7) and a
// sub-sample on the surface flipped by round-off of sin (1e-3 of one voxel's
// fraction of 8192: below 1e-6 of C). Tolerance: 1e-6 of max |C|.
TEST(PlainWeave, BalancedWeaveIsSymmetricAndWithinVoigtReuss) {
  const micro::CellSpec spec = micro::readCell(
      std::string(LAMINA_SOURCE_DIR) + "/cases/cells/plain-weave.toml", micro::lazyCatalog());
  const micro::UnitCell cell = micro::buildCell(spec, {32, 32, 8});
  ASSERT_FALSE(cell.composites.empty());
  const std::vector<Stiffness> C = spec.stiffnessesAt(1.0);
  const micro::VoxelMaterials vm = micro::voxelMaterials(cell, C, spec.densities());
  homogenize::Options o;
  o.tol = 1e-8;
  homogenize::Homogenizer h(homogenize::gridOf(cell), vm.phase, vm.C, vm.density, o);
  const Matrix6 Ce = h.run().C.matrix();
  const double tol = 1e-6 * Ce.cwiseAbs().maxCoeff();
  expectPlainWeaveSymmetry(Ce, tol);
  // in-plane stiffer than through the thickness (the yarns lie in the plane)
  EXPECT_GT(Ce(0, 0), Ce(2, 2));
  // Voigt/Reuss at the voxel fractions (composite voxels count their
  // sub-voxel fractions; a laminate voxel lies between its phases' Reuss and
  // Voigt means, so the bounds of the phase fractions still hold)
  expectWithinVoigtReuss(Ce, C, cell.voxel_fraction);
}

} // namespace
} // namespace lamina::test
