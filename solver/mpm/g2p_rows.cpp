#include "solver/mpm/g2p_rows.hpp"

#include <immintrin.h>

#include "solver/mpm/parallel.hpp"
#include "solver/mpm/stencil_row.hpp"

namespace pdmpm::mpm {

namespace {

void prefetch_moved(const G2PArrays2& a, bool remap, Index p) {
  __builtin_prefetch(a.velocity + p);
  __builtin_prefetch(a.displacement + p);
  if (remap) __builtin_prefetch(a.mass + p);
}

IVec<2> node_stride(const G2PArrays2& a) { return IVec<2>(1, a.row_stride); }
IVec<3> node_stride(const G2PArrays3& a) { return a.stride; }

// The reference, 2D and 3D: Simulation's generic G2P with 3 nodes per axis.
template <int D, class Arrays>
bool g2p_rows_scalar(const Arrays& a, G2PParameters q, Index k_begin, Index k_end) {
  const IVec<D> stride = node_stride(a);
  bool finite = true;
  for (Index k = k_begin; k < k_end; ++k) {
    if constexpr (D == 2)
      if (k + kPrefetchAhead < k_end) prefetch_moved(a, q.remap, a.order[k + kPrefetchAhead]);
    const Index p = a.order[k];
    Vec<D> v_pic = Vec<D>::Zero(), dv = Vec<D>::Zero();
    for_each_grid_node<D, 3>(a.stencil[k], stride, [&](Index node, double w, const Vec<D>&) {
      v_pic += w * a.grid_velocity_new[node];
      dv += w * (a.grid_velocity_new[node] - a.grid_velocity[node]);
    });
    a.velocity[p] = q.flip * (a.velocity[p] + dv) + (1.0 - q.flip) * v_pic;
    a.displacement[p] += q.dt * v_pic;
    finite = finite && a.velocity[p].allFinite() && a.displacement[p].allFinite();
    if (q.remap) {
      const Vec<D> mv = a.mass[p] * a.velocity[p];
      for_each_grid_node<D, 3>(a.stencil[k], stride,
                               [&](Index node, double w, const Vec<D>&) { a.grid_momentum[node] += w * mv; });
    }
  }
  return finite;
}

// Particle p's new velocity (the FLIP / PIC blend) and displacement from Σ S v_new and
// Σ S (v_new − v), the low and high halves of sums; finite becomes false if either is not.
__attribute__((target("avx2"), always_inline)) inline __m128d move_particle(const G2PArrays2& a, G2PParameters q,
                                                                            Index p, __m256d sums, bool& finite) {
  const __m128d v_pic = _mm256_castpd256_pd128(sums), dv = _mm256_extractf128_pd(sums, 1);
  double* vp = a.velocity[p].data();
  double* up = a.displacement[p].data();
  const __m128d v = _mm_add_pd(_mm_mul_pd(_mm_set1_pd(q.flip), _mm_add_pd(_mm_loadu_pd(vp), dv)),
                               _mm_mul_pd(_mm_set1_pd(1.0 - q.flip), v_pic));
  const __m128d u = _mm_add_pd(_mm_loadu_pd(up), _mm_mul_pd(_mm_set1_pd(q.dt), v_pic));
  _mm_storeu_pd(vp, v);
  _mm_storeu_pd(up, u);
  // x − x = 0 exactly for finite x, NaN for ±∞ and NaN.
  const __m128d zero = _mm_setzero_pd();
  finite = finite && _mm_movemask_pd(_mm_cmpeq_pd(_mm_sub_pd(v, v), zero)) == 3 &&
      _mm_movemask_pd(_mm_cmpeq_pd(_mm_sub_pd(u, u), zero)) == 3;
  return v;
}

__attribute__((target("avx512f"))) bool g2p_rows_avx512(const G2PArrays2& a, G2PParameters q, Index k_begin,
                                                        Index k_end) {
  const __mmask8 six = 0x3f;  // a row's three nodes, x and y
  bool finite = true;
  for (Index k = k_begin; k < k_end; ++k) {
    if (k + kPrefetchAhead < k_end) prefetch_moved(a, q.remap, a.order[k + kPrefetchAhead]);
    const Index p = a.order[k];
    const Stencil<2>& st = a.stencil[k];
    const std::array<double, 3>& x = st.w[0];
    const __m512d wx2 = _mm512_set_pd(0.0, 0.0, x[2], x[2], x[1], x[1], x[0], x[0]);  // node i's in lanes 2i, 2i + 1
    const Index base = st.first[0] + st.first[1] * a.row_stride;
    __m256d sums = _mm256_setzero_pd();  // Σ S v_new and Σ S (v_new − v): x, y of each
    __m512d w2[3];                       // S of the row's node i in lanes 2i, 2i + 1; the remap uses them again
    for (int j = 0; j < 3; ++j) {
      const Index row = base + j * a.row_stride;
      w2[j] = _mm512_mul_pd(wx2, _mm512_set1_pd(st.w[1][j]));
      const __m512d vn = _mm512_maskz_loadu_pd(six, a.grid_velocity_new[row].data());
      const __m512d vo = _mm512_maskz_loadu_pd(six, a.grid_velocity[row].data());
      const __m512d c_pic = _mm512_mul_pd(w2[j], vn), c_dv = _mm512_mul_pd(w2[j], _mm512_sub_pd(vn, vo));
      for (int i = 0; i < 3; ++i) sums = _mm256_add_pd(sums, node_pairs(c_pic, c_dv, i));  // as the scalar sum
    }
    const __m128d v = move_particle(a, q, p, sums, finite);
    if (q.remap) {
      const double m = a.mass[p], mvx = m * v[0], mvy = m * v[1];
      const __m512d mv3 = _mm512_set_pd(0.0, 0.0, mvy, mvx, mvy, mvx, mvy, mvx);  // m v per node
      for (int j = 0; j < 3; ++j) {
        double* at = a.grid_momentum[base + j * a.row_stride].data();
        _mm512_mask_storeu_pd(at, six, _mm512_add_pd(_mm512_maskz_loadu_pd(six, at), _mm512_mul_pd(w2[j], mv3)));
      }
    }
  }
  return finite;
}

// The same below AVX-512, a row as a 256-bit and a 128-bit register (Row2, stencil_row.hpp).
__attribute__((target("avx2"))) bool g2p_rows_avx2(const G2PArrays2& a, G2PParameters q, Index k_begin, Index k_end) {
  bool finite = true;
  for (Index k = k_begin; k < k_end; ++k) {
    if (k + kPrefetchAhead < k_end) prefetch_moved(a, q.remap, a.order[k + kPrefetchAhead]);
    const Index p = a.order[k];
    const Stencil<2>& st = a.stencil[k];
    const Row2 wx = per_node(st.w[0]);
    const Index base = st.first[0] + st.first[1] * a.row_stride;
    __m256d sums = _mm256_setzero_pd();  // Σ S v_new and Σ S (v_new − v): x, y of each
    Row2 w[3];                           // S of the row's nodes in their x, y lanes; the remap uses them again
    for (int j = 0; j < 3; ++j) {
      const Index row = base + j * a.row_stride;
      w[j] = times(wx, st.w[1][j]);
      const Row2 vn = load_row(a.grid_velocity_new[row].data()), vo = load_row(a.grid_velocity[row].data());
      const Row2 c_pic = mul(w[j], vn), c_dv = mul(w[j], sub(vn, vo));
      for (int i = 0; i < 3; ++i) sums = _mm256_add_pd(sums, node_pairs(c_pic, c_dv, i));  // as the scalar sum
    }
    const __m128d v = move_particle(a, q, p, sums, finite);
    if (q.remap) {
      const double m = a.mass[p];
      const Row2 mv = every_node(m * v[0], m * v[1]);
      for (int j = 0; j < 3; ++j) {
        double* at = a.grid_momentum[base + j * a.row_stride].data();
        store_row(at, add(load_row(at), mul(w[j], mv)));
      }
    }
  }
  return finite;
}

__attribute__((target("avx512f"))) bool g2p_rows3_avx512(const G2PArrays3& a, G2PParameters q, Index k_begin,
                                                         Index k_end) {
  const __mmask8 xyz = 0x07;
  const __m512d flip = _mm512_set1_pd(q.flip), pic = _mm512_set1_pd(1.0 - q.flip), dt = _mm512_set1_pd(q.dt);
  bool finite = true;
  for (Index k = k_begin; k < k_end; ++k) {
    const Index p = a.order[k];
    const Stencil<3>& st = a.stencil[k];
    const Index base = st.first[0] + st.first[1] * a.stride[1] + st.first[2] * a.stride[2];
    __m512d v_pic = _mm512_setzero_pd(), dv = v_pic;
    __m512d w[9];  // S of the row's nodes per lane; the remap uses them again
    double w2[9];  // node 2's, for the ninth double
    for (int l = 0; l < 3; ++l)
      for (int j = 0; j < 3; ++j) {
        const int r = 3 * l + j;
        const Index row = base + j * a.stride[1] + l * a.stride[2];
        const Row3Shape shape = row3_shape(st, j, l, false);
        w[r] = shape.w, w2[r] = shape.w2;
        const double* vn_at = a.grid_velocity_new[row].data();
        const double* vo_at = a.grid_velocity[row].data();
        const __m512d vn = _mm512_loadu_pd(vn_at), vo = _mm512_loadu_pd(vo_at);
        const __m512d c_pic = _mm512_mul_pd(w[r], vn), c_dv = _mm512_mul_pd(w[r], _mm512_sub_pd(vn, vo));
        const double pic9 = w2[r] * vn_at[8], dv9 = w2[r] * (vn_at[8] - vo_at[8]);
        for (int i = 0; i < 3; ++i) {  // node by node, as the scalar sum
          v_pic = _mm512_add_pd(v_pic, row_node(c_pic, pic9, i));
          dv = _mm512_add_pd(dv, row_node(c_dv, dv9, i));
        }
      }
    double* vp = a.velocity[p].data();
    double* up = a.displacement[p].data();
    const __m512d v = _mm512_add_pd(_mm512_mul_pd(flip, _mm512_add_pd(_mm512_maskz_loadu_pd(xyz, vp), dv)),
                                    _mm512_mul_pd(pic, v_pic));
    const __m512d u = _mm512_add_pd(_mm512_maskz_loadu_pd(xyz, up), _mm512_mul_pd(dt, v_pic));
    _mm512_mask_storeu_pd(vp, xyz, v);
    _mm512_mask_storeu_pd(up, xyz, u);
    // x − x = 0 exactly for finite x, NaN for ±∞ and NaN (lanes 3–7 are zero).
    const __m512d zero = _mm512_setzero_pd();
    finite = finite && _mm512_cmp_pd_mask(_mm512_sub_pd(v, v), zero, _CMP_EQ_OQ) == 0xff &&
        _mm512_cmp_pd_mask(_mm512_sub_pd(u, u), zero, _CMP_EQ_OQ) == 0xff;
    if (q.remap) {
      const double m = a.mass[p];
      const Vec<3> mv(m * vp[0], m * vp[1], m * vp[2]);
      const __m512d mv8 = row_lanes(mv);
      for (int l = 0; l < 3; ++l)
        for (int j = 0; j < 3; ++j) {
          const int r = 3 * l + j;
          double* at = a.grid_momentum[base + j * a.stride[1] + l * a.stride[2]].data();
          _mm512_storeu_pd(at, _mm512_add_pd(_mm512_loadu_pd(at), _mm512_mul_pd(w[r], mv8)));
          at[8] += w2[r] * mv[2];
        }
    }
  }
  return finite;
}

// The same below AVX-512 (Row3, stencil_row.hpp); a particle's x, y, z in lanes 0–2.
__attribute__((target("avx2"))) bool g2p_rows3_avx2(const G2PArrays3& a, G2PParameters q, Index k_begin, Index k_end) {
  const __m256d flip = _mm256_set1_pd(q.flip), pic = _mm256_set1_pd(1.0 - q.flip), dt = _mm256_set1_pd(q.dt);
  bool finite = true;
  for (Index k = k_begin; k < k_end; ++k) {
    const Index p = a.order[k];
    const Stencil<3>& st = a.stencil[k];
    const Index base = st.first[0] + st.first[1] * a.stride[1] + st.first[2] * a.stride[2];
    __m256d v_pic = _mm256_setzero_pd(), dv = v_pic;
    for (int l = 0; l < 3; ++l)
      for (int j = 0; j < 3; ++j) {
        const Index row = base + j * a.stride[1] + l * a.stride[2];
        const Row3ShapeAvx2 shape = row3_shape_avx2(st, j, l, false);
        const Row3& w = shape.w;
        const double w2 = shape.w2;
        const double* vn_at = a.grid_velocity_new[row].data();
        const double* vo_at = a.grid_velocity[row].data();
        const Row3 vn = load_row3(vn_at), vo = load_row3(vo_at);
        const Row3 c_pic = mul(w, vn), c_dv = mul(w, sub(vn, vo));
        const double pic9 = w2 * vn_at[8], dv9 = w2 * (vn_at[8] - vo_at[8]);
        for (int i = 0; i < 3; ++i) {  // node by node, as the scalar sum
          v_pic = _mm256_add_pd(v_pic, row3_node(c_pic, pic9, i));
          dv = _mm256_add_pd(dv, row3_node(c_dv, dv9, i));
        }
      }
    double* vp = a.velocity[p].data();
    double* up = a.displacement[p].data();
    const __m256d v = _mm256_add_pd(_mm256_mul_pd(flip, _mm256_add_pd(load_xyz(vp), dv)), _mm256_mul_pd(pic, v_pic));
    const __m256d u = _mm256_add_pd(load_xyz(up), _mm256_mul_pd(dt, v_pic));
    store_xyz(vp, v);
    store_xyz(up, u);
    // x − x = 0 exactly for finite x, NaN for ±∞ and NaN (lane 3 is zero).
    const __m256d zero = _mm256_setzero_pd();
    finite = finite && _mm256_movemask_pd(_mm256_cmp_pd(_mm256_sub_pd(v, v), zero, _CMP_EQ_OQ)) == 0xf &&
        _mm256_movemask_pd(_mm256_cmp_pd(_mm256_sub_pd(u, u), zero, _CMP_EQ_OQ)) == 0xf;
    if (q.remap) {
      const __m256d mv4 = _mm256_mul_pd(_mm256_set1_pd(a.mass[p]), v);  // m v, lane 3 zero
      for (int l = 0; l < 3; ++l)
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) {  // node by node (add_to_node)
            double* at = a.grid_momentum[base + i + j * a.stride[1] + l * a.stride[2]].data();
            add_to_node(at, _mm256_mul_pd(_mm256_set1_pd(st.w[0][i] * st.w[1][j] * st.w[2][l]), mv4));
          }
    }
  }
  return finite;
}

}  // namespace

std::vector<LaneVariant<G2PRows3Function>> g2p_rows3_variants() {
  // No SSE2 rows: that machine runs the scalar reference.
  return lane_variants<G2PRows3Function>(g2p_rows_scalar<3>, g2p_rows3_avx2, g2p_rows3_avx512);
}

bool g2p_rows3(const G2PArrays3& arrays, G2PParameters parameters, Index k_begin, Index k_end) {
  static const G2PRows3Function chosen = choose_lane_variant(g2p_rows3_variants());
  return chosen(arrays, parameters, k_begin, k_end);
}

std::vector<LaneVariant<G2PRowsFunction>> g2p_rows_variants() {
  // No SSE2 rows: that machine runs the scalar reference.
  return lane_variants<G2PRowsFunction>(g2p_rows_scalar<2>, g2p_rows_avx2, g2p_rows_avx512);
}

bool g2p_rows(const G2PArrays2& arrays, G2PParameters parameters, Index k_begin, Index k_end) {
  static const G2PRowsFunction chosen = choose_lane_variant(g2p_rows_variants());
  return chosen(arrays, parameters, k_begin, k_end);
}

}  // namespace pdmpm::mpm
