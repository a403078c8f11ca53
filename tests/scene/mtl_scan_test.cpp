// The MTL layer of the input contract (host/scene/mtl_scan.cpp, through load_scene): every
// numeric statement the loader reads (Kd, Ks, Ke, Ni, illum) is rejected with the MTL's
// name, line, material and value when it is not a finite number in range; near misses
// load with the values written.
#include <fstream>

#include "scene/scene_test_util.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

// mesh.obj (one triangle, material "m") with m.mtl beside it, under a JSON light.
class MtlInput : public test::ScratchDirTest {
protected:
    std::filesystem::path write(const std::string& mtl) {
        std::ofstream(dir_ / "mesh.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl m\nf 1 3 2\n";
        std::ofstream(dir_ / "m.mtl", std::ios::binary) << mtl;
        std::ofstream(dir_ / "s.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
            "objects": [{"mesh": "mesh.obj"}],
            "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}]})";
        return dir_ / "s.json";
    }
};

struct BadMtl {
    const char* name;
    const char* mtl;    ///< the MTL text; material "m" is on line 1
    const char* where;  ///< "m.mtl:<line>"
    const char* value;  ///< the offending value as quoted in the message
    const char* what;
};

class BadMtlInput : public MtlInput, public ::testing::WithParamInterface<BadMtl> {};

TEST_P(BadMtlInput, NamesFileLineMaterialAndValue) {
    const std::string e = test::load_error(write(GetParam().mtl));
    EXPECT_CONTAINS(e, GetParam().where);
    EXPECT_CONTAINS(e, "material 'm'");
    EXPECT_CONTAINS(e, GetParam().value);
    EXPECT_CONTAINS(e, GetParam().what);
}

INSTANTIATE_TEST_SUITE_P(
    Mtl, BadMtlInput,
    ::testing::Values(
        // Kd, Ks, Ke: three finite numbers >= 0 (tinyobjloader reads "nan" as 0 and a
        // single number r as (r, 0, 0)).
        BadMtl{"KdNan", "newmtl m\nKd nan 0.5 0.5\n", "m.mtl:2:", "'nan'", "Kd value 'nan' is not a number"},
        BadMtl{"KdInf", "newmtl m\nKd 0.5 inf 0.5\n", "m.mtl:2:", "'inf'", "not a number"},
        BadMtl{"KdOverflow", "newmtl m\nKd 0.5 0.5 1e39\n", "m.mtl:2:", "'1e39'", "not finite"},
        BadMtl{"KdNegative", "newmtl m\nKd -0.1 0.5 0.5\n", "m.mtl:2:", "'-0.1'", "negative (must be >= 0)"},
        BadMtl{"KdOneNumber", "newmtl m\nKd 0.5\n", "m.mtl:2:", "'Kd 0.5'", "needs 3 numbers (r g b)"},
        BadMtl{"KdFourNumbers", "newmtl m\nKd 0.5 0.5 0.5 0.5\n", "m.mtl:2:", "'Kd 0.5 0.5 0.5 0.5'", "needs 3 numbers"},
        BadMtl{"KdSpectral", "newmtl m\nKd spectral wood.rfl\n", "m.mtl:2:", "'Kd spectral wood.rfl'",
               "spectral and xyz forms are not supported"},
        BadMtl{"KdDecimalComma", "newmtl m\nKd 0,5 0.5 0.5\n", "m.mtl:2:", "'0,5'", "not a number"},
        BadMtl{"KdCommentTooEarly", "newmtl m\nKd 0.5 # 0.5 0.5\n", "m.mtl:2:", "'Kd 0.5 # 0.5 0.5'", "needs 3"},
        BadMtl{"KsNan", "newmtl m\nKs 0 nan 0\n", "m.mtl:2:", "'nan'", "Ks value"},
        BadMtl{"KsNegative", "newmtl m\nKs 0 0 -1\n", "m.mtl:2:", "'-1'", "negative"},
        BadMtl{"KeInf", "newmtl m\nKe inf 1 1\n", "m.mtl:2:", "'inf'", "Ke value 'inf' is not a number"},
        BadMtl{"KeOverflow", "newmtl m\nKe 1e40 1 1\n", "m.mtl:2:", "'1e40'", "not finite"},
        BadMtl{"KeNegative", "newmtl m\nKe -5 0 0\n", "m.mtl:2:", "'-5'", "negative"},
        BadMtl{"KeAboveTheLimit", "newmtl m\nKe 1 2e15 1\n", "m.mtl:2:", "'2e15'", "exceeds the limit of 1e+15 W/(sr"},
        BadMtl{"KeTwoNumbers", "newmtl m\nKe 1 1\n", "m.mtl:2:", "'Ke 1 1'", "needs 3 numbers"},
        // Ni: one finite number >= 0, and > 0 in a dielectric (illum 7), before or after illum.
        BadMtl{"NiNan", "newmtl m\nNi nan\n", "m.mtl:2:", "'nan'", "Ni value 'nan' is not a number"},
        BadMtl{"NiInf", "newmtl m\nNi 1e39\n", "m.mtl:2:", "'1e39'", "not finite"},
        BadMtl{"NiNegative", "newmtl m\nNi -1.5\n", "m.mtl:2:", "'-1.5'", "negative"},
        BadMtl{"NiTwoNumbers", "newmtl m\nNi 1.5 2\n", "m.mtl:2:", "'Ni 1.5 2'", "Ni needs 1 number"},
        BadMtl{"NiZeroDielectric", "newmtl m\nillum 7\nNi 0\n", "m.mtl:3:", "Ni '0'",
               "dielectric (illum 7): the index of refraction must be > 0"},
        BadMtl{"NiZeroBeforeIllum", "newmtl m\nNi 0.0\nillum 7\nnewmtl other\n", "m.mtl:2:", "Ni '0.0'", "must be > 0"},
        // illum: one integer 0..10.
        BadMtl{"IllumEleven", "newmtl m\nillum 11\n", "m.mtl:2:", "'11'", "not an MTL illumination model (0..10)"},
        BadMtl{"IllumNegative", "newmtl m\nillum -1\n", "m.mtl:2:", "'-1'", "0..10"},
        BadMtl{"IllumFraction", "newmtl m\nillum 2.5\n", "m.mtl:2:", "'illum 2.5'", "illum needs 1 integer"},
        BadMtl{"IllumWord", "newmtl m\nillum glass\n", "m.mtl:2:", "'illum glass'", "illum needs 1 integer"},
        BadMtl{"IllumOverflow", "newmtl m\nillum 99999999999999999999\n", "m.mtl:2:", "'99999999999999999999'",
               "0..10"},
        // map_Kd: a file name (tinyobjloader took the bare statement as no texture).
        BadMtl{"MapKdWithoutFile", "newmtl m\nKd 1 1 1\nmap_Kd # none\n", "m.mtl:3:", "map_Kd",
               "map_Kd needs a texture file name"},
        // Names.
        BadMtl{"DefinedTwice", "newmtl m\nKd 1 1 1\nnewmtl m\nKd 0 0 0\n", "m.mtl:3:", "first at",
               "m.mtl:1)"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_F(MtlInput, NulByteIsRejected) {
    const std::string e = test::load_error(write(std::string("newmtl m\nKd 1 1 1") + '\0' + "\n"));
    EXPECT_CONTAINS(e, "m.mtl:2: contains a NUL byte");
}

TEST_F(MtlInput, ByteOrderMarkIsRejected) {
    const std::string e = test::load_error(write("\xEF\xBB\xBFnewmtl m\nKd 1 1 1\n"));
    EXPECT_CONTAINS(e, "m.mtl:1: starts with a UTF-8 byte-order mark");
}

TEST_F(MtlInput, MissingMtlNamesTheObjLine) {
    write("newmtl m\n");
    std::filesystem::remove(dir_ / "m.mtl");
    const std::string e = test::load_error(dir_ / "s.json");
    EXPECT_CONTAINS(e, (dir_ / "m.mtl").string() + ": MTL file (mtllib at " + (dir_ / "mesh.obj").string() + ":1) not found");
}

TEST_F(MtlInput, MtlThatIsADirectory) {
    write("");
    std::filesystem::remove(dir_ / "m.mtl");
    std::filesystem::create_directories(dir_ / "m.mtl");
    const std::string e = test::load_error(dir_ / "s.json");
    EXPECT_CONTAINS(e, (dir_ / "m.mtl").string() + ": MTL file");
    EXPECT_CONTAINS(e, "is a directory");
}

// A statement the loader reads that comes before any newmtl belongs to no material:
// tinyobjloader dropped it without a word.
TEST_F(MtlInput, StatementBeforeAnyNewmtlIsRejected) {
    for (const char* statement : {"Kd 1 1 1", "Ke 1 1 1", "Ni 1.5", "illum 2", "map_Kd t.png"}) {
        const std::string e = test::load_error(write(std::string(statement) + "\nnewmtl m\nKd 1 1 1\n"));
        EXPECT_CONTAINS(e, "m.mtl:1: before any newmtl: ");
        EXPECT_CONTAINS(e, "belongs to no material");
    }
}

// A texture whose content is refused is named with the map_Kd line that names it.
TEST_F(MtlInput, TextureContentErrorNamesTheMapKdLine) {
    std::ofstream(dir_ / "bad.png") << "not an image";
    const std::string e = test::load_error(write("newmtl m\nKd 1 1 1\nmap_Kd bad.png\n"));
    EXPECT_CONTAINS(e, "bad.png: texture is not a PNG or JPEG image");
    EXPECT_CONTAINS(e, "(map_Kd of ");
    EXPECT_CONTAINS(e, "m.mtl:3: material 'm')");
    std::filesystem::remove(dir_ / "bad.png");
    EXPECT_CONTAINS(test::load_error(write("newmtl m\nKd 1 1 1\nmap_Kd bad.png\n")), "m.mtl:3: material 'm')");
}

// The boundaries of each range are valid, and values are read as written (Kd and Ks
// clamped to 1), so the checks above cannot be passing by rejecting everything.
TEST_F(MtlInput, BoundaryValuesLoad) {
    const Scene s = load_scene(write("# header\r\n"
                                     "newmtl m\r\n"
                                     "\tKd 0 0.5 1.5   # blue above 1: clamped\r\n"
                                     "\tKs 0 0 0\r\n"
                                     "\tKe 0 1e15 2\r\n"  // limits::kMaxRadiance, the brightest accepted
                                     "\tNi 1e-3\r\n"
                                     "\tillum 7\r\n"
                                     "\tNs 1e999\r\n"  // not read: not checked
                                     "newmtl lambert\r\nNi 0\r\nillum 0\r\n"
                                     "newmtl top\r\nillum 10\r\n"),
                               DataPath{});
    const Material& m = s.materials[s.material[0]];
    EXPECT_EQ(m.name, "m");
    EXPECT_EQ(m.albedo, glm::vec3(0.0f, 0.5f, 1.0f));
    EXPECT_EQ(m.emission, glm::vec3(0.0f, 1e15f, 2.0f));
    EXPECT_EQ(m.illum, 7);
    EXPECT_FLOAT_EQ(m.ior, 1e-3f);
}

}  // namespace
}  // namespace tessera
