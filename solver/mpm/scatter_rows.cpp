#include "solver/mpm/scatter_rows.hpp"

#include <immintrin.h>

#include "solver/mpm/parallel.hpp"
#include "solver/mpm/stencil_row.hpp"

namespace pdmpm::mpm {

namespace {

// A particle whose external force is zero adds only zeros to f_ext of its nodes, and
// adding ±0 to a sum that starts at +0 leaves its bits as they are (a sum of such
// terms is never −0): skipping it is exact. In a hybrid run only the transition
// particles carry one (the coupling force), a few per cent of the grid's particles.
template <int D>
bool carries_external_force(const Vec<D>& fe) {
  return !fe.isZero(0.0);
}

void prefetch_scattered(const ScatterSource2& s, ScatterFields what, Index p) {
  __builtin_prefetch(s.mass + p);
  __builtin_prefetch(s.velocity + p);
  if (what.forces) {
    __builtin_prefetch(s.volume + p);
    __builtin_prefetch(s.external + p);
    for (const double* tau : s.tau) __builtin_prefetch(tau + p);
  }
}

IVec<2> node_stride(const ScatterTarget2& g) { return IVec<2>(1, g.row_stride); }
IVec<3> node_stride(const ScatterTarget3& g) { return g.stride; }
// The particle's stress (2D: its in-plane block).
Mat<2> tau_of(const ScatterSource2& s, Index p) {
  return (Mat<2>() << s.tau[0][p], s.tau[2][p], s.tau[1][p], s.tau[3][p]).finished();
}
Mat<3> tau_of(const ScatterSource3& s, Index p) { return s.tau->get(p); }

// The reference, 2D and 3D: Simulation's generic scatter with 3 nodes per axis.
template <int D, class Source, class Target>
void scatter_rows_scalar(const Source& s, const Target& g, ScatterFields what, Index k_begin, Index k_end) {
  const IVec<D> stride = node_stride(g);
  for (Index k = k_begin; k < k_end; ++k) {
    if constexpr (D == 2)
      if (k + kPrefetchAhead < k_end) prefetch_scattered(s, what, s.order[k + kPrefetchAhead]);
    const Index p = s.order[k];
    const double m = s.mass[p];
    const Vec<D> mv = m * s.velocity[p];
    const Mat<D> Vtau = s.volume[p] * tau_of(s, p);
    const Vec<D> fe = s.external[p];
    const bool external = what.external && carries_external_force(fe);
    for_each_grid_node<D, 3>(s.stencil[k], stride, [&](Index node, double w, const Vec<D>& grad) {
      if (what.mass) g.mass[node] += w * m;
      if (what.momentum) g.momentum[node] += w * mv;
      if (what.forces) {
        g.force_internal[node] -= Vtau * grad;
        if (external) g.force_external[node] += w * fe;
      }
    });
  }
}

// One stencil row per instruction: lanes 0–2 are the row's three nodes (mass), lanes
// 0–5 their x, y pairs (vectors). Masked loads and stores touch only those nodes.
__attribute__((target("avx512f"))) void scatter_rows_avx512(const ScatterSource2& s, const ScatterTarget2& g,
                                                            ScatterFields what, Index k_begin, Index k_end) {
  const __mmask8 three = 0x07, six = 0x3f;
  for (Index k = k_begin; k < k_end; ++k) {
    if (k + kPrefetchAhead < k_end) prefetch_scattered(s, what, s.order[k + kPrefetchAhead]);
    const Index p = s.order[k];
    const Stencil<2>& st = s.stencil[k];
    const double m = s.mass[p];
    const Vec<2> v = s.velocity[p];
    const double mvx = m * v[0], mvy = m * v[1];
    const __m512d mv = _mm512_set_pd(0.0, 0.0, mvy, mvx, mvy, mvx, mvy, mvx);
    const std::array<double, 3>&x = st.w[0], &dx = st.dw[0];
    const __m512d wx = _mm512_set_pd(0.0, 0.0, 0.0, 0.0, 0.0, x[2], x[1], x[0]);
    const __m512d wx2 = _mm512_set_pd(0.0, 0.0, x[2], x[2], x[1], x[1], x[0], x[0]);  // node i's in lanes 2i, 2i + 1
    const __m512d dwx2 = _mm512_set_pd(0.0, 0.0, dx[2], dx[2], dx[1], dx[1], dx[0], dx[0]);
    __m512d va = _mm512_setzero_pd(), vb = va, fe = va;
    const bool external = what.forces && what.external && carries_external_force<2>(s.external[p]);
    if (what.forces) {
      const double vol = s.volume[p];
      const double v00 = vol * s.tau[0][p], v10 = vol * s.tau[1][p], v01 = vol * s.tau[2][p], v11 = vol * s.tau[3][p];
      va = _mm512_set_pd(0.0, 0.0, v10, v00, v10, v00, v10, v00);  // −(V τ ∇S) = −(va ∂S/∂x + vb ∂S/∂y)
      vb = _mm512_set_pd(0.0, 0.0, v11, v01, v11, v01, v11, v01);
      const Vec<2> f = s.external[p];
      fe = _mm512_set_pd(0.0, 0.0, f[1], f[0], f[1], f[0], f[1], f[0]);
    }
    const Index base = st.first[0] + st.first[1] * g.row_stride;
    for (int j = 0; j < 3; ++j) {
      const Index row = base + j * g.row_stride;
      const __m512d wy = _mm512_set1_pd(st.w[1][j]);
      const __m512d w2 = _mm512_mul_pd(wx2, wy);  // S of node i in lanes 2i, 2i + 1
      if (what.mass) {
        double* at = g.mass + row;
        const __m512d w = _mm512_mul_pd(wx, wy);
        _mm512_mask_storeu_pd(at, three,
                              _mm512_add_pd(_mm512_maskz_loadu_pd(three, at), _mm512_mul_pd(w, _mm512_set1_pd(m))));
      }
      if (what.momentum) {
        double* at = g.momentum[row].data();
        _mm512_mask_storeu_pd(at, six, _mm512_add_pd(_mm512_maskz_loadu_pd(six, at), _mm512_mul_pd(w2, mv)));
      }
      if (what.forces) {
        const __m512d gx = _mm512_mul_pd(dwx2, wy), gy = _mm512_mul_pd(_mm512_set1_pd(st.dw[1][j]), wx2);
        double* at = g.force_internal[row].data();
        const __m512d f = _mm512_add_pd(_mm512_mul_pd(va, gx), _mm512_mul_pd(vb, gy));
        _mm512_mask_storeu_pd(at, six, _mm512_sub_pd(_mm512_maskz_loadu_pd(six, at), f));
        if (external) {
          double* ate = g.force_external[row].data();
          _mm512_mask_storeu_pd(ate, six, _mm512_add_pd(_mm512_maskz_loadu_pd(six, ate), _mm512_mul_pd(w2, fe)));
        }
      }
    }
  }
}

// The same below AVX-512: a row's nodes 0 and 1 in a 256-bit register, node 2 in a
// 128-bit one (Row2, stencil_row.hpp), the mass's three nodes as a pair and a scalar.
__attribute__((target("avx2"))) void scatter_rows_avx2(const ScatterSource2& s, const ScatterTarget2& g,
                                                       ScatterFields what, Index k_begin, Index k_end) {
  for (Index k = k_begin; k < k_end; ++k) {
    if (k + kPrefetchAhead < k_end) prefetch_scattered(s, what, s.order[k + kPrefetchAhead]);
    const Index p = s.order[k];
    const Stencil<2>& st = s.stencil[k];
    const double m = s.mass[p];
    const Vec<2> v = s.velocity[p];
    const Row2 mv = every_node(m * v[0], m * v[1]);
    const std::array<double, 3>& x = st.w[0];
    const __m128d wx01 = _mm_set_pd(x[1], x[0]), mass = _mm_set1_pd(m);
    const Row2 wx = per_node(x), dwx = per_node(st.dw[0]);
    Row2 va{}, vb{}, fe{};
    const bool external = what.forces && what.external && carries_external_force<2>(s.external[p]);
    if (what.forces) {
      const double vol = s.volume[p];
      const double v00 = vol * s.tau[0][p], v10 = vol * s.tau[1][p], v01 = vol * s.tau[2][p], v11 = vol * s.tau[3][p];
      va = every_node(v00, v10);  // −(V τ ∇S) = −(va ∂S/∂x + vb ∂S/∂y)
      vb = every_node(v01, v11);
      const Vec<2> f = s.external[p];
      fe = every_node(f[0], f[1]);
    }
    const Index base = st.first[0] + st.first[1] * g.row_stride;
    for (int j = 0; j < 3; ++j) {
      const Index row = base + j * g.row_stride;
      const double wy = st.w[1][j];
      const Row2 w = times(wx, wy);  // S of each node in its x, y lanes
      if (what.mass) {
        double* at = g.mass + row;
        const __m128d w01 = _mm_mul_pd(wx01, _mm_set1_pd(wy));
        _mm_storeu_pd(at, _mm_add_pd(_mm_loadu_pd(at), _mm_mul_pd(w01, mass)));
        at[2] += x[2] * wy * m;
      }
      if (what.momentum) {
        double* at = g.momentum[row].data();
        store_row(at, add(load_row(at), mul(w, mv)));
      }
      if (what.forces) {
        const Row2 gx = times(dwx, wy), gy = times(wx, st.dw[1][j]);
        double* at = g.force_internal[row].data();
        store_row(at, sub(load_row(at), add(mul(va, gx), mul(vb, gy))));
        if (external) {
          double* ate = g.force_external[row].data();
          store_row(ate, add(load_row(ate), mul(w, fe)));
        }
      }
    }
  }
}

// A row's nine doubles: lanes 0–7 and the ninth apart (stencil_row.hpp).
__attribute__((target("avx512f"))) void scatter_rows3_avx512(const ScatterSource3& s, const ScatterTarget3& g,
                                                             ScatterFields what, Index k_begin, Index k_end) {
  const __mmask8 three = 0x07, z_lanes = 0x24;  // lanes 2 and 5 hold z components
  for (Index k = k_begin; k < k_end; ++k) {
    const Index p = s.order[k];
    const Stencil<3>& st = s.stencil[k];
    const std::array<double, 3>& x = st.w[0];
    const __m512d wx3 = _mm512_set_pd(0.0, 0.0, 0.0, 0.0, 0.0, x[2], x[1], x[0]);
    const double m = s.mass[p];
    const Vec<3> mv = m * s.velocity[p];
    const __m512d mv8 = row_lanes(mv);
    Mat<3> Vtau = Mat<3>::Zero();
    Vec<3> fe = Vec<3>::Zero();
    bool external = false;
    if (what.forces) {
      Vtau = s.volume[p] * s.tau->get(p);
      fe = s.external[p];
      external = what.external && carries_external_force(fe);
    }
    const __m512d va = row_lanes(Vtau.col(0)), vb = row_lanes(Vtau.col(1)), vc = row_lanes(Vtau.col(2));
    const __m512d fe8 = row_lanes(fe);
    const Index base = st.first[0] + st.first[1] * g.stride[1] + st.first[2] * g.stride[2];
    for (int l = 0; l < 3; ++l)
      for (int j = 0; j < 3; ++j) {
        const Index row = base + j * g.stride[1] + l * g.stride[2];
        const Row3Shape shape = row3_shape(st, j, l, what.forces);
        const __m512d w = shape.w;
        const double w2 = shape.w2;
        if (what.mass) {
          double* at = g.mass + row;
          const __m512d w3 = _mm512_mul_pd(_mm512_mul_pd(wx3, _mm512_set1_pd(st.w[1][j])), _mm512_set1_pd(st.w[2][l]));
          _mm512_mask_storeu_pd(at, three,
                                _mm512_add_pd(_mm512_maskz_loadu_pd(three, at), _mm512_mul_pd(w3, _mm512_set1_pd(m))));
        }
        if (what.momentum) {
          double* at = g.momentum[row].data();
          _mm512_storeu_pd(at, _mm512_add_pd(_mm512_loadu_pd(at), _mm512_mul_pd(w, mv8)));
          at[8] += w2 * mv[2];
        }
        if (what.forces) {
          const __m512d a = _mm512_mul_pd(va, shape.gx), b = _mm512_mul_pd(vb, shape.gy),
                        c = _mm512_mul_pd(vc, shape.gz);
          const __m512d f = _mm512_mask_blend_pd(z_lanes, _mm512_add_pd(_mm512_add_pd(a, b), c),
                                                 _mm512_add_pd(a, _mm512_add_pd(b, c)));
          double* at = g.force_internal[row].data();
          _mm512_storeu_pd(at, _mm512_sub_pd(_mm512_loadu_pd(at), f));
          at[8] -= Vtau(2, 0) * shape.gx2 + (Vtau(2, 1) * shape.gy2 + Vtau(2, 2) * shape.gz2);
          if (external) {
            double* ate = g.force_external[row].data();
            _mm512_storeu_pd(ate, _mm512_add_pd(_mm512_loadu_pd(ate), _mm512_mul_pd(w, fe8)));
            ate[8] += w2 * fe[2];
          }
        }
      }
  }
}

}  // namespace

std::vector<LaneVariant<ScatterRows3Function>> scatter_rows3_variants() {
  // Below AVX-512 the scalar reference: an AVX2 form, node by node, ran no faster (rows of
  // two 256-bit stores ran at half its speed; add_to_node, stencil_row.hpp).
  return lane_variants<ScatterRows3Function>(scatter_rows_scalar<3>, scatter_rows_scalar<3>, scatter_rows3_avx512);
}

void scatter_rows3(const ScatterSource3& source, const ScatterTarget3& grid, ScatterFields what, Index k_begin,
                   Index k_end) {
  static const ScatterRows3Function chosen = choose_lane_variant(scatter_rows3_variants());
  chosen(source, grid, what, k_begin, k_end);
}

std::vector<LaneVariant<ScatterRowsFunction>> scatter_rows_variants() {
  // No SSE2 rows: that machine runs the scalar reference.
  return lane_variants<ScatterRowsFunction>(scatter_rows_scalar<2>, scatter_rows_avx2, scatter_rows_avx512);
}

void scatter_rows(const ScatterSource2& source, const ScatterTarget2& grid, ScatterFields what, Index k_begin,
                  Index k_end) {
  static const ScatterRowsFunction chosen = choose_lane_variant(scatter_rows_variants());
  chosen(source, grid, what, k_begin, k_end);
}

}  // namespace pdmpm::mpm
