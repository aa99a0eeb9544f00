// Adversarial inputs for raykit's shared functions: seeded streams of floats and vectors that
// favour what float code gets wrong, for tests/test_adversarial.cpp (>= 1e5 inputs per public
// function, CPU) and the GPU parity tests (a sample of the same stream on the driver).
//
// A float argument is described by a Floats spec: its documented domain [lo, hi], the points the
// function's doc names (domain ends, seams, poles: "marks") and whether NaN/±Inf may be fed (only
// where the doc promises to sanitise them). Each draw is, by chance:
//   - an edge value (~40%): ±0, ±denorm_min, ±largest denormal, ±FLT_MIN, 1 and its neighbours,
//     powers of ten up to ±FLT_MAX and its neighbour, the domain's ends and every mark with their
//     neighbours at 1 and 2 ulp (all restricted to [lo, hi]); NaN, ±Inf when allowed;
//   - log-uniform in magnitude over the domain, random sign (~35%);
//   - uniform over the domain's part within [-4, 4] (~15%);
//   - up to 64 ulp or a relative 2^-k from an edge value (~7%);
//   - a random finite bit pattern inside the domain (~3%).
// With 1e5 rows every edge value of an argument occurs about a thousand times and every pair of
// edge values of two arguments several times. Vectors (Vecs) mix: independent components,
// zero and signed zeros, all-denormal, axis-aligned, near-axis (tiny or denormal off-axis parts),
// huge (up to ±FLT_MAX), random directions scaled by 2^-149..2^127, mixed magnitudes
// (1e-40..1e38 in one vector), equal components (grey), random unit vectors; Vecs::units() gives
// float-normalised unit vectors only (axes, near-axis, diagonals, random).
//
// Gen records every argument it draws for the current row, so a failing check prints the exact
// inputs (%.9g and %a). RK_ADV_SCALE (environment, default 1) multiplies every row count and
// RK_ADV_SEED (default 0) changes every stream: `RK_ADV_SCALE=10 RK_ADV_SEED=7 ./test_adversarial`
// runs a longer, different search.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace rktest::adv {

inline constexpr float kDenormMin = std::numeric_limits<float>::denorm_min();
inline constexpr float kDenormMax = FLT_MIN - std::numeric_limits<float>::denorm_min();

/// Bit pattern of a float (distinguishes -0 from +0 and every NaN).
inline std::uint32_t bits(float x)
{
    std::uint32_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

/// Edge values every finite float argument receives (restricted to its domain).
inline const std::vector<float>& finite_edges()
{
    static const std::vector<float> v = [] {
        std::vector<float> e = {0.0f, kDenormMin, kDenormMax, FLT_MIN, std::nextafter(FLT_MIN, 1.0f), 1e-37f,
                                1e-30f, 1e-20f, 1e-18f, 1e-10f, 1e-7f, FLT_EPSILON, 1e-4f, 0.001f, 0.01f, 0.1f,
                                0.25f, 0.5f, std::nextafter(1.0f, 0.0f), 1.0f, std::nextafter(1.0f, 2.0f), 2.0f,
                                3.0f, 10.0f, 100.0f, 1e4f, 1e6f, 16777216.0f, 1e9f, 1e15f, 1e18f, 1e20f, 1e30f,
                                1e37f, 1e38f, std::nextafter(FLT_MAX, 0.0f), FLT_MAX};
        const size_t n = e.size();
        for (size_t i = 0; i < n; ++i) e.push_back(-e[i]);
        return e;
    }();
    return v;
}

/// A float argument's documented domain and the points its doc names.
struct Floats {
    float lo = -FLT_MAX, hi = FLT_MAX;  ///< documented domain (closed): nothing outside is drawn
    bool nonfinite = false;             ///< NaN and ±Inf are drawn too (documented sanitising)
    std::vector<float> marks;           ///< domain ends, seams, poles named by the doc
    std::vector<float> edges;           ///< derived: every edge value inside the domain

    /// Any finite float.
    static const Floats& any()
    {
        static const Floats f = range(-FLT_MAX, FLT_MAX);
        return f;
    }
    /// Any float, NaN and ±Inf included.
    static const Floats& all()
    {
        static const Floats f = [] {
            Floats a = range(-FLT_MAX, FLT_MAX);
            a.nonfinite = true;
            a.build();
            return a;
        }();
        return f;
    }
    /// Finite floats in [lo, hi].
    static Floats range(float lo, float hi)
    {
        Floats f;
        f.lo = lo;
        f.hi = hi;
        f.build();
        return f;
    }
    /// Adds documented points (each also with its neighbours at 1 and 2 ulp, inside the domain).
    /// Specs are built once, outside the row loop: building sorts out duplicate edges.
    Floats mark(std::initializer_list<float> m) const
    {
        Floats f = *this;
        f.marks.insert(f.marks.end(), m.begin(), m.end());
        f.build();
        return f;
    }
    bool contains(float x) const
    {
        if (std::isnan(x) || std::isinf(x)) return nonfinite;
        return x >= lo && x <= hi;
    }
    void build()
    {
        edges.clear();
        auto add = [&](float x) {
            if (!contains(x)) return;
            for (float e : edges) {
                if (bits(e) == bits(x)) return;
            }
            edges.push_back(x);
        };
        for (float x : finite_edges()) add(x);
        std::vector<float> points = marks;
        points.push_back(lo);
        points.push_back(hi);
        for (float m : points) {
            if (!std::isfinite(m)) continue;
            add(m);
            float up = m, down = m;
            for (int k = 0; k < 2; ++k) {
                up = std::nextafter(up, FLT_MAX);
                down = std::nextafter(down, -FLT_MAX);
                add(up);
                add(down);
            }
        }
        if (nonfinite) {
            add(std::numeric_limits<float>::quiet_NaN());
            add(std::numeric_limits<float>::infinity());
            add(-std::numeric_limits<float>::infinity());
        }
    }
};

/// A vector argument: each component's domain, or unit vectors only.
struct Vecs {
    Floats c = Floats::any();
    bool unit = false;  ///< documented as unit length: float-normalised directions only

    static Vecs of(const Floats& f)
    {
        Vecs v;
        v.c = f;
        return v;
    }
    static const Vecs& any()
    {
        static const Vecs v = of(Floats::any());
        return v;
    }
    static const Vecs& all()
    {
        static const Vecs v = of(Floats::all());
        return v;
    }
    static const Vecs& units()
    {
        static const Vecs v = [] {
            Vecs u;
            u.c = Floats::range(-1.0f, 1.0f);
            u.unit = true;
            return u;
        }();
        return v;
    }
};

/// One recorded argument of the current row.
struct Arg {
    double value;
    bool is_float;
};

/// The stream: draws arguments from specs and records them for the failure message.
class Gen {
public:
    explicit Gen(std::uint32_t seed) : rng_(seed) {}

    /// Starts a row (forgets the previous row's arguments).
    void next_row() { rec_.clear(); }

    float f(const Floats& s)
    {
        const float x = draw(s);
        rec_.push_back({x, true});
        return x;
    }
    glm::vec2 v2(const Vecs& s)
    {
        const glm::vec3 v = vec(s);
        return glm::vec2(v.x, v.y);
    }
    glm::vec3 v3(const Vecs& s) { return vec(s); }
    glm::vec4 v4(const Vecs& s)
    {
        const glm::vec3 v = vec(s);
        return glm::vec4(v, s.unit ? 0.0f : f(s.c));
    }
    /// An int from `valid` (80%) or an invalid neighbour / extreme (20%).
    int i(std::initializer_list<int> valid)
    {
        static const int extra[] = {-1, -2, 3, 4, 7, 99, std::numeric_limits<int>::min(),
                                    std::numeric_limits<int>::max()};
        const int x = uniform() < 0.8 ? *(valid.begin() + index(valid.size())) : extra[index(8)];
        rec_.push_back({static_cast<double>(x), false});
        return x;
    }
    /// One of `values` (for sizes and modes whose invalid values the test lists itself).
    int one_of(std::initializer_list<int> values)
    {
        const int x = *(values.begin() + index(values.size()));
        rec_.push_back({static_cast<double>(x), false});
        return x;
    }
    /// A uint in [lo, hi]: the ends and their neighbours, powers of two, or log-uniform.
    std::uint32_t u(std::uint32_t lo = 0u, std::uint32_t hi = 0xFFFFFFFFu)
    {
        std::uint32_t x;
        const double r = uniform();
        if (r < 0.4) {
            const std::uint32_t e[] = {lo, lo + 1u, hi, hi - 1u, 0u, 1u, 2u, 3u, 16777216u, 16777217u, 0x7FFFFFFFu,
                                       0x80000000u, 0xFFFFFFFFu, 1u << (index(32))};
            x = e[index(14)];
        } else {
            const double m = std::exp2(uniform() * 32.0);
            x = m >= 4294967295.0 ? 0xFFFFFFFFu : static_cast<std::uint32_t>(m);
        }
        if (x < lo || x > hi) x = lo + static_cast<std::uint32_t>(uniform() * (static_cast<double>(hi) - lo));
        rec_.push_back({static_cast<double>(x), false});
        return x;
    }
    /// Uniform in [0, 1) (not recorded: for choices the test makes itself).
    double uniform() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
    size_t index(size_t n) { return static_cast<size_t>(rng_() % static_cast<std::uint32_t>(n)); }

    /// The current row's arguments (the first 40).
    std::string args() const
    {
        std::string s;
        char buf[96];
        for (size_t k = 0; k < rec_.size() && k < 40; ++k) {
            const Arg& a = rec_[k];
            if (a.is_float) {
                std::snprintf(buf, sizeof buf, "%.9g (%a)", a.value, a.value);
            } else {
                std::snprintf(buf, sizeof buf, "%.0f", a.value);
            }
            s += (s.empty() ? "" : ", ") + std::string(buf);
        }
        if (rec_.size() > 40) s += ", ... (" + std::to_string(rec_.size()) + " in all)";
        return s;
    }

private:
    float draw(const Floats& s)
    {
        for (int attempt = 0; attempt < 16; ++attempt) {
            const float x = draw_once(s);
            if (s.contains(x)) return x;
        }
        return s.edges.empty() ? s.lo : s.edges[index(s.edges.size())];
    }
    float draw_once(const Floats& s)
    {
        const double r = uniform();
        if (s.nonfinite && r < 0.04) {
            const float nf[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                                -std::numeric_limits<float>::infinity()};
            return nf[index(3)];
        }
        if (r < 0.40) return s.edges[index(s.edges.size())];
        if (r < 0.75) return log_uniform(s);
        if (r < 0.90) {
            const double a = std::max(static_cast<double>(s.lo), -4.0), b = std::min(static_cast<double>(s.hi), 4.0);
            if (a > b) return log_uniform(s);
            return static_cast<float>(a + (b - a) * uniform());
        }
        if (r < 0.97) {
            float e = s.edges[index(s.edges.size())];
            if (!std::isfinite(e)) return e;
            if (uniform() < 0.5) {
                const int k = 1 + static_cast<int>(index(64));
                const float dir = uniform() < 0.5 ? FLT_MAX : -FLT_MAX;
                for (int j = 0; j < k; ++j) e = std::nextafter(e, dir);
                return e;
            }
            const double rel = std::ldexp(uniform() * 2.0 - 1.0, -static_cast<int>(index(24)));
            return static_cast<float>(static_cast<double>(e) * (1.0 + rel));
        }
        std::uint32_t u = static_cast<std::uint32_t>(rng_());
        float x;
        std::memcpy(&x, &u, sizeof x);
        return std::isfinite(x) ? x : 0.0f;
    }
    /// Log-uniform magnitude inside the domain, random sign where both signs are allowed.
    float log_uniform(const Floats& s)
    {
        const bool pos = s.hi > 0.0f, neg = s.lo < 0.0f;
        if (!pos && !neg) return 0.0f;
        const bool positive = pos && (!neg || uniform() < 0.5);
        double mmin = kDenormMin, mmax;
        if (positive) {
            if (s.lo > 0.0f) mmin = s.lo;
            mmax = s.hi;
        } else {
            if (s.hi < 0.0f) mmin = -static_cast<double>(s.hi);
            mmax = -static_cast<double>(s.lo);
        }
        const double l0 = std::log2(mmin), l1 = std::log2(mmax);
        const float m = static_cast<float>(std::exp2(l0 + (l1 - l0) * uniform()));
        return positive ? m : -m;
    }
    float signed_(float m) { return uniform() < 0.5 ? m : -m; }
    float pick(std::initializer_list<float> v) { return *(v.begin() + index(v.size())); }
    glm::vec3 unit_random()
    {
        std::normal_distribution<float> n(0.0f, 1.0f);
        for (;;) {
            glm::vec3 v(n(rng_), n(rng_), n(rng_));
            const float l = glm::length(v);
            if (l > 1e-3f) return v / l;
        }
    }
    glm::vec3 unit_vec()
    {
        const size_t k = index(6);
        glm::vec3 v;
        if (k == 0) {
            v = glm::vec3(0.0f);
            v[static_cast<int>(index(3))] = signed_(1.0f);
            // Signed zeros in the other components.
            for (int j = 0; j < 3; ++j) {
                if (v[j] == 0.0f) v[j] = signed_(0.0f);
            }
        } else if (k == 1) {
            v = glm::vec3(0.0f);
            const int a = static_cast<int>(index(3));
            v[a] = signed_(1.0f);
            v[(a + 1) % 3] =
                signed_(pick({kDenormMin, kDenormMax, FLT_MIN, 1e-30f, 1e-20f, 1e-8f, 1e-4f, FLT_EPSILON}));
            v = glm::normalize(v);
        } else if (k == 2) {
            v = glm::normalize(glm::vec3(signed_(1.0f), signed_(1.0f), signed_(1.0f)));
            v[static_cast<int>(index(3))] *= uniform() < 0.5 ? 1.0f : 0.0f;
            v = glm::normalize(v);
        } else {
            v = unit_random();
        }
        return v;
    }
    glm::vec3 vec(const Vecs& s)
    {
        glm::vec3 v;
        if (s.unit) {
            v = unit_vec();
        } else {
            v = raw_vec(s);
            for (int j = 0; j < 3; ++j) {
                if (!s.c.contains(v[j])) v[j] = draw(s.c);
            }
        }
        rec_.push_back({v.x, true});
        rec_.push_back({v.y, true});
        rec_.push_back({v.z, true});
        return v;
    }
    glm::vec3 raw_vec(const Vecs& s)
    {
        const double r = uniform();
        if (r < 0.30) return glm::vec3(draw(s.c), draw(s.c), draw(s.c));
        if (r < 0.33) return glm::vec3(signed_(0.0f), signed_(0.0f), signed_(0.0f));
        if (r < 0.38) {
            auto tiny = [&] { return signed_(pick({0.0f, kDenormMin, kDenormMax, FLT_MIN, 1e-30f})); };
            return glm::vec3(tiny(), tiny(), tiny());
        }
        if (r < 0.48) {
            glm::vec3 v(signed_(0.0f), signed_(0.0f), signed_(0.0f));
            v[static_cast<int>(index(3))] = draw(s.c);
            return v;
        }
        if (r < 0.58) {
            const float m = uniform() < 0.5 ? signed_(1.0f) : draw(s.c);
            glm::vec3 v;
            for (int j = 0; j < 3; ++j) {
                v[j] = signed_(pick({0.0f, kDenormMin, kDenormMax, FLT_MIN, 1e-20f, 1e-8f, FLT_EPSILON}) *
                               (uniform() < 0.5 ? 1.0f : std::abs(m)));
            }
            v[static_cast<int>(index(3))] = m;
            return v;
        }
        if (r < 0.63) {
            auto huge = [&] { return signed_(static_cast<float>(std::exp2(100.0 + 28.0 * uniform()))); };
            glm::vec3 v(huge(), huge(), huge());
            if (uniform() < 0.3) v[static_cast<int>(index(3))] = signed_(FLT_MAX);
            return v;
        }
        if (r < 0.78) {
            const float scale = static_cast<float>(std::exp2(-149.0 + 276.0 * uniform()));
            return unit_random() * scale;
        }
        if (r < 0.85) {
            auto mixed = [&] {
                return signed_(pick({1e-40f, 1e-30f, 1e-20f, 1e-7f, 1.0f, 1e7f, 1e20f, 1e30f, 1e38f}));
            };
            return glm::vec3(mixed(), mixed(), mixed());
        }
        if (r < 0.95) return glm::vec3(draw(s.c));
        return unit_random();
    }

    std::mt19937 rng_;
    std::vector<Arg> rec_;
};

/// Environment knobs: RK_ADV_SCALE multiplies row counts, RK_ADV_SEED changes every stream.
inline double scale()
{
    const char* e = std::getenv("RK_ADV_SCALE");
    const double s = e ? std::atof(e) : 1.0;
    return s > 0.0 ? s : 1.0;
}
inline std::uint32_t seed_for(const std::string& name)
{
    const char* e = std::getenv("RK_ADV_SEED");
    std::uint32_t h = 2166136261u ^ static_cast<std::uint32_t>(e ? std::strtoul(e, nullptr, 10) : 0ul);
    for (char ch : name) h = (h ^ static_cast<unsigned char>(ch)) * 16777619u;
    return h;
}

/// Outcome of one function's sweep: inputs (rows, plus what a body adds for rows with many
/// inputs), failed checks and the first few failures.
struct Tally {
    std::string name;
    long rows = 0, fails = 0;
    double seconds = 0.0;
    std::vector<std::string> first;

    void fail(const Gen& g, const std::string& what)
    {
        ++fails;
        if (first.size() < 5) first.push_back(what + "  <- args " + g.args());
    }
    std::string summary() const
    {
        std::string s = name + ": " + std::to_string(fails) + " of " + std::to_string(rows) + " rows failed";
        for (const std::string& f : first) s += "\n    " + f;
        return s;
    }
};

/// Runs `body(gen, tally)` for `rows` rows (times RK_ADV_SCALE) on the stream seeded by `name`.
template <class Body>
Tally sweep(const std::string& name, long rows, Body&& body)
{
    const auto start = std::chrono::steady_clock::now();
    Tally t;
    t.name = name;
    Gen g(seed_for(name));
    const long n = static_cast<long>(static_cast<double>(rows) * scale());
    for (long i = 0; i < n; ++i) {
        g.next_row();
        body(g, t);
    }
    t.rows += n;  // a body may count extra inputs of its row (texels of a bake)
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return t;
}

inline bool finite(float x) { return std::isfinite(x); }
inline bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
inline bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool finite(glm::vec4 v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }
/// lo <= x <= hi (false for NaN).
inline bool within(float x, float lo, float hi) { return x >= lo && x <= hi; }
inline bool within(glm::vec2 v, float lo, float hi) { return within(v.x, lo, hi) && within(v.y, lo, hi); }
inline bool within(glm::vec3 v, float lo, float hi)
{
    return within(v.x, lo, hi) && within(v.y, lo, hi) && within(v.z, lo, hi);
}
inline bool within(glm::vec4 v, float lo, float hi) { return within(glm::vec3(v), lo, hi) && within(v.w, lo, hi); }

}  // namespace rktest::adv
