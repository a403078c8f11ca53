// The OBJ layer of the input contract (host/scene/obj_scan.cpp, through load_scene): each
// malformed OBJ is rejected with the OBJ's name, the line and the offending value; each
// near-miss that is valid OBJ still loads.
#include <fstream>

#include "scene/scene_test_util.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 0 1\n";

// broken.obj (and m.mtl when given) beside a scene that places it under a JSON light.
class ObjInput : public test::ScratchDirTest {
protected:
    std::filesystem::path write(const std::string& obj, const std::string& mtl = "") {
        std::ofstream(dir_ / "broken.obj", std::ios::binary) << obj;
        if (!mtl.empty()) std::ofstream(dir_ / "m.mtl", std::ios::binary) << mtl;
        std::ofstream(dir_ / "s.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
            "objects": [{"mesh": "broken.obj"}],
            "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}]})";
        return dir_ / "s.json";
    }
};

struct BadObj {
    const char* name;
    std::string obj;
    const char* where;  ///< "broken.obj:<line>" (or the file the message must start with)
    const char* value;  ///< the offending value as the message quotes it
    const char* what;   ///< the reason
};

class BadObjInput : public ObjInput, public ::testing::WithParamInterface<BadObj> {};

TEST_P(BadObjInput, NamesFileLineAndValue) {
    const std::string e = test::load_error(write(GetParam().obj, "newmtl x\nKd 1 1 1\n"));
    EXPECT_CONTAINS(e, GetParam().where);
    EXPECT_CONTAINS(e, GetParam().value);
    EXPECT_CONTAINS(e, GetParam().what);
    EXPECT_EQ(e.find("Failed parse"), std::string::npos) << "tinyobjloader's own text leaked: " << e;
}

const std::string T = kTriangle;

INSTANTIATE_TEST_SUITE_P(
    Obj, BadObjInput,
    ::testing::Values(
        // tinyobjloader's skin weights (vw): it casts joint ids to int, so an id that is not
        // finite or beyond an int would be undefined behaviour in the parser.
        BadObj{"SkinJointInfinite", T + "vw 1 1e999 0.5\nf 1 2 3\n", "broken.obj:4:", "'1e999'",
               "joint id '1e999' is not a float in [0, 2^31)"},
        BadObj{"SkinJointAboveInt", T + "vw 1 0 0.5 2147483647 0.5\nf 1 2 3\n", "broken.obj:4:", "'2147483647'",
               "is not a float in [0, 2^31)"},
        BadObj{"SkinJointNegative", T + "vw 1 -1 0.5\nf 1 2 3\n", "broken.obj:4:", "'-1'", "is not a float in"},
        BadObj{"SkinWeightNotANumber", T + "vw 1 0 heavy\nf 1 2 3\n", "broken.obj:4:", "'heavy'", "is not a number"},
        BadObj{"SkinVertexOverflow", T + "vw 99999999999 0 1\nf 1 2 3\n", "broken.obj:4:", "vw 99999999999",
               "needs a vertex index that fits an int"},
        // Faces with too few corners (tinyobjloader drops them without an error).
        BadObj{"TwoCorners", T + "f 1 2\n", "broken.obj:4:", "'f 1 2'", "face has 2 corners (needs at least 3)"},
        BadObj{"OneCorner", T + "f 1\n", "broken.obj:4:", "'f 1'", "face has 1 corner"},
        BadObj{"NoCorner", T + "f\n", "broken.obj:4:", "'f'", "face has 0 corners"},
        BadObj{"LineOneCorner", T + "f 1 2 3\nl 1\n", "broken.obj:5:", "'l 1'", "line has 1 corner"},
        // Indices: overflow (atoi would make it -1, the last vertex), range, zero, syntax.
        BadObj{"IndexOverflow", T + "f 1 2 99999999999999999999\n", "broken.obj:4:", "'99999999999999999999'",
               "out of range"},
        BadObj{"IndexAboveInt", T + "f 1 2 4294967298\n", "broken.obj:4:", "'4294967298'", "out of range"},
        BadObj{"NegativeOverflow", T + "f 1 2 -99999999999999999999\n", "broken.obj:4:", "'-99999999999999999999'",
               "out of range"},
        BadObj{"OnePastTheEnd", T + "f 1 2 4\n", "broken.obj:4:", "'4'", "out of range (the file has 3)"},
        BadObj{"RelativeBeforeStart", T + "f -4 1 2\n", "broken.obj:4:", "'-4'", "3 defined before this line"},
        BadObj{"RelativeBeforeDefined", "v 0 0 0\nf -1 -2 1\nv 1 0 0\nv 0 0 1\n", "broken.obj:2:", "'-2'",
               "1 defined before this line"},
        BadObj{"ZeroVertex", T + "f 0 1 2\n", "broken.obj:4:", "vertex index 0", "OBJ indices start at 1"},
        BadObj{"ZeroNormal", T + "vn 0 1 0\nf 1//0 2//1 3//1\n", "broken.obj:5:", "normal index 0", "start at 1"},
        BadObj{"ZeroTexcoord", T + "vt 0 0\nf 1/0 2/1 3/1\n", "broken.obj:5:", "texcoord index 0", "start at 1"},
        BadObj{"ZeroInALine", T + "f 1 2 3\nl 0 1\n", "broken.obj:5:", "vertex index 0", "start at 1"},
        BadObj{"NormalOutOfRange", T + "vn 0 1 0\nf 1//1 2//2 3//1\n", "broken.obj:5:", "'2'", "out of range"},
        BadObj{"TexcoordOutOfRange", T + "vt 0 0\nf 1/1 2/5 3/1\n", "broken.obj:5:", "'5'", "out of range"},
        BadObj{"FractionalIndex", T + "f 1.5 2 3\n", "broken.obj:4:", "'1.5'", "not an integer"},
        BadObj{"LetterIndex", T + "f 1 2 3a\n", "broken.obj:4:", "'3a'", "not an integer"},
        BadObj{"TrailingSlash", T + "f 1/ 2 3\n", "broken.obj:4:", "'1/'", "is not v, v/vt, v//vn or v/vt/vn"},
        BadObj{"FourParts", T + "f 1/1/1/1 2 3\n", "broken.obj:4:", "'1/1/1/1'", "is not v, v/vt"},
        // Vertex data tinyobjloader reads as 0 (or as a prefix of the token).
        BadObj{"NanVertex", "v 0 0 0\nv 1 0 nan\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "'nan'", "not a number"},
        BadObj{"InfVertex", "v 0 0 0\nv 1 0 inf\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "'inf'", "not a number"},
        BadObj{"FloatOverflow", "v 0 0 0\nv 1 0 1e39\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "'1e39'", "not finite"},
        BadObj{"DecimalComma", "v 0 0 0\nv 1,5 0 0\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "'1,5'", "not a number"},
        BadObj{"HexFloat", "v 0 0 0\nv 0x10 0 0\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "'0x10'", "not a number"},
        BadObj{"TwoCoordinates", "v 0 0 0\nv 1 0\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "'v 1 0'",
               "needs 3 to 6 numbers, got 2"},
        BadObj{"NanTexcoord", T + "vt nan 0\nf 1/1 2/1 3/1\n", "broken.obj:4:", "'nan'", "texture coordinate (vt)"},
        BadObj{"TexcoordOverflow", T + "vt 0 -5e40\nf 1/1 2/1 3/1\n", "broken.obj:4:", "'-5e40'", "not finite"},
        BadObj{"NanNormal", T + "vn 0 nan 0\nf 1//1 2//1 3//1\n", "broken.obj:4:", "'nan'", "normal (vn)"},
        BadObj{"TwoNumberNormal", T + "vn 0 1\nf 1//1 2//1 3//1\n", "broken.obj:4:", "'vn 0 1'", "needs 3 numbers"},
        // mtllib and usemtl.
        BadObj{"MtllibOutside", "mtllib ../../m.mtl\n" + T + "f 1 2 3\n", "broken.obj:1:", "'../../m.mtl'",
               "not a file name beside the OBJ"},
        BadObj{"MtllibAbsolute", "mtllib /etc/m.mtl\n" + T + "f 1 2 3\n", "broken.obj:1:", "'/etc/m.mtl'",
               "beside the OBJ"},
        BadObj{"MtllibSubfolder", "mtllib sub/m.mtl\n" + T + "f 1 2 3\n", "broken.obj:1:", "'sub/m.mtl'",
               "beside the OBJ"},
        BadObj{"MtllibTwoFiles", "mtllib m.mtl other.mtl\n" + T + "f 1 2 3\n", "broken.obj:1:", "names 2 files",
               "one mtllib line per MTL file"},
        BadObj{"MtllibMissing", "mtllib gone.mtl\n" + T + "f 1 2 3\n", "gone.mtl: MTL file", "broken.obj:1",
               "not found"},
        BadObj{"UsemtlWithoutMtllib", T + "usemtl x\nf 1 2 3\n", "broken.obj:4:", "usemtl 'x'",
               "no mtllib line comes before it"},
        BadObj{"UsemtlUnknown", "mtllib m.mtl\n" + T + "usemtl nothing\nf 1 2 3\n", "broken.obj:5:",
               "usemtl 'nothing'", "m.mtl (defining x)"},
        BadObj{"UsemtlBeforeMtllib", T + "usemtl x\nmtllib m.mtl\nf 1 2 3\n", "broken.obj:4:", "usemtl 'x'",
               "no mtllib line comes before it"},
        // Whole-file problems.
        BadObj{"NulByte", std::string("v 0 0 0\nv 1 0 0") + '\0' + "\nv 0 0 1\nf 1 2 3\n", "broken.obj:2:", "NUL byte",
               "not a text file"},
        // A byte-order mark made the first vertex an unknown statement: indices shifted by one.
        BadObj{"ByteOrderMark", "\xEF\xBB\xBF" + T + "f 1 2 3\n", "broken.obj:1:", "byte-order mark",
               "save the file without it"},
        BadObj{"NoFaces", "# no faces\nv 0 0 0\n", "broken.obj:", "no f lines", "has no faces"},
        BadObj{"OnlyPoints", T + "p 1 2 3\n", "broken.obj:", "no f lines", "has no faces"}),
    [](const auto& info) { return std::string(info.param.name); });

// Near misses of the cases above that are valid OBJ: they must load, with the triangles
// they describe (so the checks are not simply rejecting everything).
TEST_F(ObjInput, ValidVariantsLoad) {
    const std::string obj =
        "# comment\r\n"
        "mtllib m.mtl\r\n"
        "  v 0 0 0 1   # w coordinate and a comment\r\n"
        "v 1 0 0\r\n"
        "v\t0\t0\t1\r\n"
        "v +1.0e0 .0 -0.\r\n"
        "vt 0.5\r\n"
        "vn 0 1 0\r\n"
        "vw 1 0 0.25 2147483520 -0.5\r\n"  // skin weights, ignored; the largest float id below 2^31
        "usemtl x\r\n"
        "f 1/1/1 3/1/1 2/1/1\r\n"
        "f -4//-1 -2//-1 -1//1\r\n"  // relative indices
        "f 1 3 4 2\r\n";             // a quad: two triangles
    const Scene s = load_scene(write(obj, "newmtl x\nKd 2 0.5 0.25 # above 1: clamped\nNi 0\n"), DataPath{});
    ASSERT_EQ(s.triangle_count(), 4u + 2u);  // + the JSON light
    EXPECT_EQ(s.positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(s.positions[1], glm::vec3(0, 0, 1));
    EXPECT_EQ(s.positions[5], glm::vec3(1, 0, 0));  // -1 is the 4th vertex, defined last
    EXPECT_EQ(s.uvs[0], glm::vec2(0.5f, 0.0f));
    EXPECT_EQ(s.materials[s.material[0]].albedo, glm::vec3(1.0f, 0.5f, 0.25f));
}

TEST_F(ObjInput, ConvexPentagonGivesThreeTriangles) {
    const Scene s = load_scene(write("v 0 0 0\nv 2 0 0\nv 3 0 1\nv 1 0 2\nv -1 0 1\nf 1 5 4 3 2\n"), DataPath{});
    EXPECT_EQ(s.triangle_count(), 3u + 2u);
}

TEST_F(ObjInput, MeshThatIsADirectory) {
    std::filesystem::create_directories(dir_ / "broken.obj");
    std::ofstream(dir_ / "s.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
        "objects": [{"mesh": "broken.obj"}]})";
    const std::string e = test::load_error(dir_ / "s.json");
    EXPECT_CONTAINS(e, (dir_ / "broken.obj").string());
    EXPECT_CONTAINS(e, "is a directory");
    EXPECT_CONTAINS(e, "objects[0].mesh");
    EXPECT_EQ(e.find("not found"), std::string::npos) << e;
}

}  // namespace
}  // namespace tessera
