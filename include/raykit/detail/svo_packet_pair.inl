// raykit — detail/svo_packet_pair.inl: lane traits made of two lane traits side by side, for the
// packet walk of svo_trace_packet.hpp (detail/svo_packet_walk.inl). svo_trace_packet.hpp includes
// it once per pair with
//   RK_SVO_LP_NAME    the traits' name,
//   RK_SVO_LP_HALF    the traits of one half (Lanes8: AVX2, Lanes16: AVX-512),
//   RK_SVO_LP_TARGET  the halves' target attribute,
// defined, and undefines them after. Not a header of its own: no include guard on purpose.
//
// Every lane value is one register of the half's traits per half (rays 0 .. H::N - 1, then
// H::N .. 2 H::N - 1), with the half's operations on each; masks likewise. A walk with these
// traits (RK_SVO_PW_HALVES) expands a node whose rays all lie in one half on that half's lanes.
struct RK_SVO_LP_NAME {
    using H = RK_SVO_LP_HALF;
    static constexpr int N = 2 * H::N;
    struct V {
        typename H::V a, b;
    };
    struct M {
        typename H::M a, b;
    };
    struct I {
        typename H::I a, b;
    };
    static constexpr unsigned kHalf = (1u << H::N) - 1u;
    RK_SVO_LP_TARGET static V load(const float* p) { return V{H::load(p), H::load(p + H::N)}; }
    RK_SVO_LP_TARGET static V set1(float x) { return V{H::set1(x), H::set1(x)}; }
    RK_SVO_LP_TARGET static V zero() { return V{H::zero(), H::zero()}; }
    RK_SVO_LP_TARGET static I zero_i() { return I{H::zero_i(), H::zero_i()}; }
    RK_SVO_LP_TARGET static V mul(V x, V y) { return V{H::mul(x.a, y.a), H::mul(x.b, y.b)}; }
    RK_SVO_LP_TARGET static V sub(V x, V y) { return V{H::sub(x.a, y.a), H::sub(x.b, y.b)}; }
    RK_SVO_LP_TARGET static V add(V x, V y) { return V{H::add(x.a, y.a), H::add(x.b, y.b)}; }
    RK_SVO_LP_TARGET static V max(V x, V y) { return V{H::max(x.a, y.a), H::max(x.b, y.b)}; }
    RK_SVO_LP_TARGET static V min(V x, V y) { return V{H::min(x.a, y.a), H::min(x.b, y.b)}; }
    RK_SVO_LP_TARGET static V close_end(V h, V t, V u) { return V{H::close_end(h.a, t.a, u.a), H::close_end(h.b, t.b, u.b)}; }
    RK_SVO_LP_TARGET static V next_up(V x) { return V{H::next_up(x.a), H::next_up(x.b)}; }
    RK_SVO_LP_TARGET static M mask_of(unsigned m) { return M{H::mask_of(m & kHalf), H::mask_of(m >> H::N)}; }
    RK_SVO_LP_TARGET static unsigned lt_bits(V x, V y) { return H::lt_bits(x.a, y.a) | (H::lt_bits(x.b, y.b) << H::N); }
    RK_SVO_LP_TARGET static unsigned le_bits(V x, V y) { return H::le_bits(x.a, y.a) | (H::le_bits(x.b, y.b) << H::N); }
    RK_SVO_LP_TARGET static M lt_and(V x, V y, M m) { return M{H::lt_and(x.a, y.a, m.a), H::lt_and(x.b, y.b, m.b)}; }
    RK_SVO_LP_TARGET static M and_not(M x, M y) { return M{H::and_not(x.a, y.a), H::and_not(x.b, y.b)}; }
    RK_SVO_LP_TARGET static unsigned bits(M m) { return H::bits(m.a) | (H::bits(m.b) << H::N); }
    RK_SVO_LP_TARGET static I blend_k(M m, I x, int k) { return I{H::blend_k(m.a, x.a, k), H::blend_k(m.b, x.b, k)}; }
    RK_SVO_LP_TARGET static V blend(M m, V x, V y) { return V{H::blend(m.a, x.a, y.a), H::blend(m.b, x.b, y.b)}; }
    RK_SVO_LP_TARGET static void store(float* p, V v)
    {
        H::store(p, v.a);
        H::store(p + H::N, v.b);
    }
    RK_SVO_LP_TARGET static void store_i(int32_t* p, I v)
    {
        H::store_i(p, v.a);
        H::store_i(p + H::N, v.b);
    }
    RK_SVO_LP_TARGET static V pick(I k, int bit, V x, V y) { return V{H::pick(k.a, bit, x.a, y.a), H::pick(k.b, bit, x.b, y.b)}; }
    RK_SVO_LP_TARGET static void entry_normal(V tx, V ty, V tz, V ux, V uy, V uz, float* nx, float* ny, float* nz)
    {
        H::entry_normal(tx.a, ty.a, tz.a, ux.a, uy.a, uz.a, nx, ny, nz);
        H::entry_normal(tx.b, ty.b, tz.b, ux.b, uy.b, uz.b, nx + H::N, ny + H::N, nz + H::N);
    }
    // One ray's brick resolution does not depend on the packet's width.
    static constexpr bool kBrickHit = H::kBrickHit;
    RK_SVO_LP_TARGET static int brick_hit(const glm::vec3& p, float q, const glm::vec3& c, const glm::vec3& b, float t0, float th,
                                          float tl, uint64_t occ, float& lo_out)
    {
        return H::brick_hit(p, q, c, b, t0, th, tl, occ, lo_out);
    }
};

#undef RK_SVO_LP_NAME
#undef RK_SVO_LP_HALF
#undef RK_SVO_LP_TARGET
