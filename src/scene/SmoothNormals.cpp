// Smooth normals on all cores. The corners are grouped by position in a flat open-addressing
// table (one per thread, each thread owning the positions whose hash falls in its part), then
// listed per position in ascending corner order (counts, then a fill): each vertex normal sums the
// same terms in the same order as a serial pass over the triangles, so the normals are the same
// whatever the thread count.
#include "scene/SmoothNormals.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "base/LargeArray.h"
#include "base/Parallel.h"

namespace gpurt {

namespace {

constexpr size_t kChunk = 16384;  // triangles a worker takes at a time
constexpr uint32_t kNone = UINT32_MAX;

// -0 and +0 are one position.
uint32_t keyBits(float c) {
    if (c == 0.0f) c = 0.0f;
    uint32_t bits;
    std::memcpy(&bits, &c, 4);
    return bits;
}

uint64_t positionHash(const glm::vec3& p) {
    uint64_t h = 0;
    for (int i = 0; i < 3; ++i) h = h * 0x9e3779b97f4a7c15ull + keyBits(p[i]);
    return h ^ (h >> 29) ^ (h >> 47);
}

bool usable(const TriangleNormals& n) {
    for (const glm::vec3& v : {n.n0, n.n1, n.n2})
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || v == glm::vec3(0.0f)) return false;
    return true;
}

const glm::vec3& corner(const Triangle& t, uint32_t k) { return k == 0 ? t.v0 : (k == 1 ? t.v1 : t.v2); }

// Positions to ids, linear probing; the table doubles when half full.
class PositionTable {
  public:
    explicit PositionTable(size_t expected) {
        size_t capacity = 64;
        while (capacity < expected * 2) capacity *= 2;
        resize(capacity);
    }
    // The id of p, a new one (next) if p is new.
    uint32_t id(const glm::vec3& p, uint64_t hash, uint32_t& next) {
        if (2 * (count_ + 1) > slots_.size()) grow();
        for (size_t i = size_t(hash) & mask_;; i = (i + 1) & mask_) {
            Slot& s = slots_[i];
            if (s.id == kNone) {
                s = Slot{p, next, hash};
                ++count_;
                return next++;
            }
            if (s.position == p) return s.id;
        }
    }

  private:
    struct Slot {
        glm::vec3 position;
        uint32_t id;
        uint64_t hash;
    };
    void resize(size_t capacity) {
        slots_.resize(capacity);
        std::fill(slots_.begin(), slots_.end(), Slot{glm::vec3(0.0f), kNone, 0});
        mask_ = capacity - 1;
    }
    void grow() {
        LargeArray<Slot> old;
        old.swap(slots_);
        resize(old.size() * 2);
        for (const Slot& s : old) {
            if (s.id == kNone) continue;
            size_t i = size_t(s.hash) & mask_;
            while (slots_[i].id != kNone) i = (i + 1) & mask_;
            slots_[i] = s;
        }
    }
    LargeArray<Slot> slots_;
    size_t mask_ = 0;
    size_t count_ = 0;
};

}  // namespace

namespace {

// Keeps the file's usable normals (fromFile[t]), clears the others; whether any is missing.
bool keepFileNormals(Scene& scene, int threads, std::vector<uint8_t>& fromFile) {
    const size_t n = scene.triangles.size();
    std::atomic<bool> anyMissing{false};
    parallelChunks(n, kChunk, threads, [&](size_t begin, size_t end, size_t) {
        bool missing = false;
        for (size_t t = begin; t < end; ++t) {
            fromFile[t] = usable(scene.normals[t]);
            if (!fromFile[t]) {
                scene.normals[t] = TriangleNormals{};
                missing = true;
            }
        }
        if (missing) anyMissing = true;
    });
    return anyMissing;
}

// Unit face normals and corner angles in double (zero for degenerate triangles).
void faceNormalsAndAngles(const Scene& scene, int threads, LargeArray<glm::dvec3>& face, LargeArray<glm::dvec3>& angle) {
    parallelChunks(scene.triangles.size(), kChunk, threads, [&](size_t begin, size_t end, size_t) {
        for (size_t t = begin; t < end; ++t) {
            face[t] = angle[t] = glm::dvec3(0.0);
            const Triangle& tri = scene.triangles[t];
            const glm::dvec3 p[3] = {tri.v0, tri.v1, tri.v2};
            const glm::dvec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
            const double len = glm::length(c);
            if (!(len > 0.0) || !std::isfinite(len)) continue;
            face[t] = c / len;
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
                const double la = glm::length(a), lb = glm::length(b);
                angle[t][k] = la > 0.0 && lb > 0.0 ? std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)) : 0.0;
            }
        }
    });
}

// The corners that share each position: vertexOf[c], corner c's position id (kNone for a
// degenerate triangle's), and the corners of position v, ascending: corners[start[v] ..
// start[v + 1]).
struct SharedCorners {
    LargeArray<uint32_t> vertexOf, start, corners;
};

// Each corner's position id: part p of the ids is thread p's (the hash's top bits), numbered
// from its own base; the bases follow once every part is counted. Then the corners at each
// position: counts, offsets, then a fill in corner order (so each list stays ascending).
SharedCorners shareCorners(const Scene& scene, int threads, const LargeArray<glm::dvec3>& face) {
    const size_t n = scene.triangles.size();
    const size_t parts = size_t(threads);
    SharedCorners s{LargeArray<uint32_t>(3 * n), {}, LargeArray<uint32_t>(3 * n)};
    std::vector<uint32_t> partCount(parts, 0);
    auto partOf = [&](uint64_t hash) { return size_t((hash >> 40) % parts); };
    parallelChunks(parts, 1, threads, [&](size_t part, size_t, size_t) {
        PositionTable table(3 * n / parts / 4 + 16);  // a mesh shares a position among ~6 corners; a soup grows it
        uint32_t next = 0;
        for (size_t t = 0; t < n; ++t) {
            if (face[t] == glm::dvec3(0.0)) {  // degenerate
                if (part == 0) s.vertexOf[3 * t] = s.vertexOf[3 * t + 1] = s.vertexOf[3 * t + 2] = kNone;
                continue;
            }
            for (uint32_t k = 0; k < 3; ++k) {
                const glm::vec3& p = corner(scene.triangles[t], k);
                const uint64_t hash = positionHash(p);
                if (partOf(hash) == part) s.vertexOf[3 * t + k] = table.id(p, hash, next);
            }
        }
        partCount[part] = next;
    });
    std::vector<uint32_t> partBase(parts + 1, 0);
    for (size_t p = 0; p < parts; ++p) partBase[p + 1] = partBase[p] + partCount[p];
    const size_t vertices = partBase[parts];

    s.start = LargeArray<uint32_t>(vertices + 1);
    std::fill(s.start.begin(), s.start.end(), 0u);
    for (size_t c = 0; c < 3 * n; ++c) {
        if (s.vertexOf[c] == kNone) continue;
        const size_t part = partOf(positionHash(corner(scene.triangles[c / 3], uint32_t(c % 3))));
        s.vertexOf[c] += partBase[part];
        ++s.start[s.vertexOf[c] + 1];
    }
    for (size_t v = 0; v < vertices; ++v) s.start[v + 1] += s.start[v];
    LargeArray<uint32_t> cursor(s.start.begin(), s.start.end() - 1);
    for (size_t c = 0; c < 3 * n; ++c)
        if (s.vertexOf[c] != kNone) s.corners[cursor[s.vertexOf[c]]++] = uint32_t(c);
    return s;
}

}  // namespace

void smoothNormals(Scene& scene, float creaseDegrees, int threadOption) {
    const size_t n = scene.triangles.size();
    if (creaseDegrees < 0.0f) {
        scene.normals.clear();
        return;
    }
    scene.normals.resize(n);
    const int threads = resolveThreads(threadOption);
    std::vector<uint8_t> fromFile(n);
    if (!keepFileNormals(scene, threads, fromFile)) return;
    LargeArray<glm::dvec3> face(n), angle(n);
    faceNormalsAndAngles(scene, threads, face, angle);
    const SharedCorners shared = shareCorners(scene, threads, face);

    const double cosCrease = std::cos(double(creaseDegrees) * M_PI / 180.0);
    parallelChunks(n, kChunk, threads, [&](size_t begin, size_t end, size_t) {
        for (size_t t = begin; t < end; ++t) {
            if (fromFile[t] || face[t] == glm::dvec3(0.0)) continue;  // degenerate: no normals, faceted
            glm::vec3 out[3];
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = shared.vertexOf[3 * t + size_t(k)];
                glm::dvec3 sum(0.0);
                for (uint32_t i = shared.start[v]; i < shared.start[v + 1]; ++i) {
                    const uint32_t c = shared.corners[i];
                    const size_t other = c / 3;
                    // Faces within the crease angle, either winding (meshes are not always consistent).
                    const double d = glm::dot(face[other], face[t]);
                    if (std::fabs(d) < cosCrease && other != t) continue;
                    sum += (d < 0.0 ? -1.0 : 1.0) * angle[other][c % 3] * face[other];
                }
                const double len = glm::length(sum);
                out[k] = glm::vec3(len > 0.0 ? sum / len : face[t]);
            }
            scene.normals[t] = {out[0], out[1], out[2]};
        }
    });
}

}  // namespace gpurt
