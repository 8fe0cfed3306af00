// Packed scene encoding and decoding. The writer lays the sections out in a fixed order with
// zero padding, so the bytes depend only on the scene and its structure. The reader checks in the
// order that lets each check trust the previous ones: magic, version, header size, file size,
// CRC-32 (zlib), section table, each section's size against its counts (before allocating), and
// last the contents (validateScene, which the writer runs too so that it never writes a file
// the reader would refuse).
#include "raytrace/scene/PackedScene.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>

#include <zlib.h>

#include "image/AtomicFile.h"
#include "image/InputError.h"
#include "raytrace/common/PackedBytes.h"
#include "raytrace/scene/packed/Sections.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

// The scene's sections in the order the writer stores them (scene/packed/Sections.h); the
// acceleration structure's (its accelerator's, accel/Accelerator.h) follow RNDR. The reader
// reads them in this order too, so that a section may rely on those before it (a lens on the
// camera, per-material sections on the materials, the maps on the textures).
constexpr const packed::SceneSection* kSectionOrder[] = {
    &packed::kTriangleSection,  &packed::kMaterialSection,    &packed::kLightSection, &packed::kCameraSection,
    &packed::kBackgroundSection, &packed::kRenderSection,     &packed::kNormalSection, &packed::kAnimationSection,
    &packed::kTexcoordSection,  &packed::kTextureSection,     &packed::kModelSection, &packed::kPbrSection,
    &packed::kEnvironmentSection, &packed::kColorSection,     &packed::kAlphaSection, &packed::kTangentSection,
    &packed::kSideSection,      &packed::kTransmissionMapSection, &packed::kLensSection, &packed::kGlowSection,
    &packed::kLightKindSection, &packed::kLayerSection, &packed::kVolumeSection, &packed::kFilmSection,
    &packed::kAnisotropySection, &packed::kThinSection, &packed::kDispersionSection};
// Where the structure's sections go: after this one.
constexpr const packed::SceneSection* kStructureAfter = &packed::kRenderSection;

// More sections than a version-1 file can hold is a damaged table, not a big scene.
constexpr uint32_t kMaxSections = 64;

std::string hex32(uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08x", value);
    return text;
}

uint32_t crc32Of(std::span<const unsigned char> bytes) {
    return static_cast<uint32_t>(
        crc32_z(crc32_z(0L, Z_NULL, 0), bytes.data(), static_cast<z_size_t>(bytes.size())));
}

// Everything about the contents that rendering relies on; `name` prefixes each message. Shared by
// the writer (name = the source scene) and the reader (name = the packed file).
void validateScene(const std::string& name, const LoadedScene& loaded) {
    const FileLoc file{name};
    const Scene& scene = loaded.scene;
    packed::checkTriangles(file, scene);
    packed::checkMaterials(file, scene);
    packed::checkTextures(file, scene);
    packed::checkColors(file, scene);
    packed::checkTangents(file, scene);
    packed::checkLights(file, scene);
    packed::checkCameras(file, scene);
    packed::checkRenderSettings(file, loaded);
}

struct Section {
    std::string tag;
    uint64_t offset = 0, size = 0;
};

// The section table: each known scene section's entry, by its place in kSectionOrder, and the
// acceleration structure's, whole: its accelerator and its sections in that one's order.
struct SectionTable {
    std::array<std::optional<Section>, std::size(kSectionOrder)> scene;
    const AcceleratorInfo* accelerator = nullptr;
    std::vector<Section> structure;
};

size_t sectionIndex(std::string_view tag) {
    for (size_t k = 0; k < std::size(kSectionOrder); ++k)
        if (tag == kSectionOrder[k]->tag) return k;
    return std::size(kSectionOrder);
}

// The accelerator a section tag is one of, or null.
const AcceleratorInfo* acceleratorOf(std::string_view tag) {
    for (const AcceleratorInfo* a : accelerators())
        if (std::find(a->sections.begin(), a->sections.end(), tag) != a->sections.end()) return a;
    return nullptr;
}

// "the grid's (GRID, CELL, LIST) or the bvh's (BVHN, BVHL)", from the registry.
std::string structureSections() {
    std::string text;
    for (const AcceleratorInfo* a : accelerators()) {
        if (!text.empty()) text += a == accelerators().back() ? " or " : ", ";
        text += "the " + std::string(a->name) + "'s (";
        for (size_t k = 0; k < a->sections.size(); ++k) text += (k ? ", " : "") + std::string(a->sections[k]);
        text += ")";
    }
    return text;
}

// Magic and version first: a later version may lay out (and checksum) the rest differently. Then
// the file's size against the header's and the checksum.
void checkHeader(std::span<const unsigned char> bytes, const FileLoc& file) {
    const size_t size = bytes.size();
    const size_t magicSize = sizeof kPackedSceneMagic - 1;
    if (size > 0 && std::memcmp(bytes.data(), kPackedSceneMagic, std::min(size, magicSize)) != 0)
        failAt(file, "not a packed gpurt scene (wrong magic '" +
                         printable(std::string_view(reinterpret_cast<const char*>(bytes.data()),
                                                    std::min(size, magicSize))) +
                         "', expected " + std::string(kPackedSceneMagic) + ")");
    if (size < 12)
        failAt(file, "truncated: " + std::to_string(size) + " bytes, less than the " +
                         std::to_string(kPackedHeaderBytes) + "-byte header");
    const uint32_t version = load32(bytes.data() + 8);
    if (version != kPackedSceneVersion)
        failAt(file, "unknown packed format version " + std::to_string(version) +
                         " (this gpurt reads version " + std::to_string(kPackedSceneVersion) + ")");
    if (size < kPackedHeaderBytes)
        failAt(file, "truncated: " + std::to_string(size) + " bytes, less than the " +
                         std::to_string(kPackedHeaderBytes) + "-byte header");
    const uint64_t declared = load64(bytes.data() + 16);
    if (declared > size)
        failAt(file, "truncated: " + std::to_string(size) + " of the " + std::to_string(declared) +
                         " bytes the header gives");
    if (declared < size)
        failAt(file, std::to_string(size) + " bytes, but the header gives " + std::to_string(declared) +
                         " (trailing data or a damaged header)");
    const uint32_t stored = load32(bytes.data() + 12);
    const uint32_t computed = crc32Of(bytes.subspan(16));
    if (stored != computed)
        failAt(file, "checksum mismatch (the contents have CRC-32 " + hex32(computed) +
                         ", the header says " + hex32(stored) + "): the file is damaged");
}

// The section table of a file whose header was checked: known tags, none twice, each section
// after the one before and inside the file, every required one present.
SectionTable readSectionTable(std::span<const unsigned char> bytes, const FileLoc& file) {
    const size_t size = bytes.size();
    const uint32_t sectionCount = load32(bytes.data() + 24);
    if (load32(bytes.data() + 28) != 0) failAt(file, "reserved header field is not 0");
    if (sectionCount > kMaxSections ||
        kPackedHeaderBytes + uint64_t(sectionCount) * kPackedSectionEntryBytes > size)
        failAt(file, "section table of " + std::to_string(sectionCount) + " entries does not fit the " +
                         std::to_string(size) + "-byte file");
    SectionTable sections;
    bool mixed = false;  // sections of two accelerators
    uint64_t end = kPackedHeaderBytes + uint64_t(sectionCount) * kPackedSectionEntryBytes;
    for (uint32_t k = 0; k < sectionCount; ++k) {
        const unsigned char* entry =
            bytes.data() + kPackedHeaderBytes + size_t(k) * kPackedSectionEntryBytes;
        Section s;
        s.tag.assign(reinterpret_cast<const char*>(entry), 4);
        s.offset = load64(entry + 8);
        s.size = load64(entry + 16);
        const size_t index = sectionIndex(s.tag);
        const AcceleratorInfo* accelerator = acceleratorOf(s.tag);
        if (index == sections.scene.size() && !accelerator)
            failAt(file, "unknown section '" + printable(s.tag) + "'");
        if (load32(entry + 4) != 0) failAt(file, "section " + s.tag + ": reserved field is not 0");
        const bool twice = accelerator ? std::any_of(sections.structure.begin(), sections.structure.end(),
                                                     [&](const Section& t) { return t.tag == s.tag; })
                                       : bool(sections.scene[index]);
        if (twice) failAt(file, "section " + s.tag + " appears twice");
        // Sections follow the table in table order, 8-byte aligned, without overlapping.
        if (s.offset % 8 != 0 || s.offset < end || s.offset > size || s.size > size - s.offset)
            failAt(file, "section " + s.tag + " (offset " + std::to_string(s.offset) + ", " +
                             std::to_string(s.size) + " bytes) does not fit the " + std::to_string(size) +
                             "-byte file");
        end = s.offset + s.size;
        if (!accelerator) {
            sections.scene[index] = s;
        } else {
            mixed = mixed || (sections.accelerator && sections.accelerator != accelerator);
            sections.accelerator = accelerator;
            sections.structure.push_back(s);
        }
    }
    for (size_t k = 0; k < std::size(kSectionOrder); ++k)
        if (!sections.scene[k] && kSectionOrder[k]->required)
            failAt(file, std::string("section ") + kSectionOrder[k]->tag + " is missing");
    // One acceleration structure, whole: one accelerator's sections, all of them; they are put in
    // its order for its reader.
    const AcceleratorInfo* a = sections.accelerator;
    std::vector<Section> ordered;
    if (a && !mixed)
        for (std::string_view tag : a->sections)
            for (const Section& s : sections.structure)
                if (s.tag == tag) ordered.push_back(s);
    if (!a || ordered.size() != a->sections.size())
        failAt(file, "the acceleration structure's sections are not one accelerator's, whole: " + structureSections());
    sections.structure = std::move(ordered);
    return sections;
}

}  // namespace

std::vector<unsigned char> encodePackedScene(const LoadedScene& loaded, const AccelStructure& accel,
                                             const std::string& name) {
    validateScene(name, loaded);
    accel.validate(FileLoc{name}, loaded.scene);

    ByteWriter out;
    out.raw(kPackedSceneMagic, sizeof kPackedSceneMagic - 1);
    out.u32(kPackedSceneVersion);
    out.u32(0);  // CRC-32, patched last
    out.u64(0);  // file size, patched last
    // Each scene section the scene needs, or the structure's (section null) by tag.
    std::vector<std::pair<std::string_view, const packed::SceneSection*>> tags;
    for (const packed::SceneSection* section : kSectionOrder) {
        if (section->required || section->present(loaded)) tags.emplace_back(section->tag, section);
        if (section == kStructureAfter)
            for (std::string_view tag : accel.accelerator().sections) tags.emplace_back(tag, nullptr);
    }
    out.u32(static_cast<uint32_t>(tags.size()));
    out.u32(0);
    const size_t table = out.size();
    for (size_t k = 0; k < tags.size(); ++k) {
        out.raw(tags[k].first.data(), 4);
        out.u32(0);
        out.u64(0);  // offset, patched below
        out.u64(0);  // size, patched below
    }

    for (size_t k = 0; k < tags.size(); ++k) {
        out.padTo(8);
        const size_t start = out.size();
        if (const packed::SceneSection* section = tags[k].second) section->write(out, loaded);
        else accel.pack(tags[k].first, out);
        const size_t entry = table + k * kPackedSectionEntryBytes;
        out.patch64(entry + 8, start);
        out.patch64(entry + 16, out.size() - start);
    }
    out.padTo(8);

    std::vector<unsigned char>& bytes = out.bytes();
    out.patch64(16, bytes.size());
    out.patch32(12, crc32Of(std::span(bytes).subspan(16)));
    return std::move(bytes);
}

void writePackedScene(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
    writeFileAtomically(path, [&](std::FILE* file) {
        if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size())
            failAt(FileLoc{path.string()}, std::string("cannot write file (") + std::strerror(errno) + ")");
    });
}

void writePackedScene(const std::filesystem::path& path, const LoadedScene& scene, const AccelStructure& accel,
                      const std::string& name) {
    writePackedScene(path, encodePackedScene(scene, accel, name));
}

LoadedScene decodePackedScene(std::span<const unsigned char> bytes, const std::string& name) {
    const FileLoc file{name};
    checkHeader(bytes, file);
    const SectionTable sections = readSectionTable(bytes, file);
    // The scene's sections in the writer's order (each may rely on those before it), each sized
    // by its counts before anything is allocated.
    auto packedSection = [&](const Section& s) {
        return PackedSection{s.tag, bytes.subspan(size_t(s.offset), size_t(s.size)), file};
    };
    LoadedScene loaded;
    for (size_t k = 0; k < std::size(kSectionOrder); ++k)
        if (const std::optional<Section>& s = sections.scene[k]) kSectionOrder[k]->read(packedSection(*s), loaded);
    validateScene(name, loaded);

    // The structure last: its accelerator reads and checks it against the checked scene.
    std::vector<PackedSection> structure;
    for (const Section& s : sections.structure) structure.push_back(packedSection(s));
    loaded.accel = sections.accelerator->unpack(structure, loaded.scene);
    return loaded;
}

LoadedScene readPackedScene(const std::filesystem::path& path) {
    const std::string bytes = readSceneFile(path);
    return decodePackedScene(std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()), path.string());
}

}  // namespace gpurt
