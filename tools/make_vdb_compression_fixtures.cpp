// Writes tests/data/vdb_zip.vdb and tests/data/vdb_uncompressed.vdb, the OpenVDB fixtures that
// pyopenvdb cannot make (its write() always uses OpenVDB's default, Blosc): the same "density"
// grid as tools/make_vdb_fixtures.py writes into vdb_density.vdb (index box 3..=7 x -2..=1 x
// 5..=7, value 0.1 * (a + 2b + 3c) + 1, a hole at (5, -1, 6) made inactive with the value 9,
// voxel size 0.5, translation (1, -2, 0.25)), saved with zip (Blender's "Zip" volume
// compression) and with no compression but the active mask.
//
// Made with the real OpenVDB library: Debian 12's libopenvdb-dev 10.0.1-2 (OpenVDB 10.0.1),
// installed with `apt-get install libopenvdb-dev libboost-dev` (its headers need Boost). Build
// and run from the repository root:
//
//     g++ -std=c++17 -O1 tools/make_vdb_compression_fixtures.cpp -lopenvdb -ltbb -lImath \
//         -o /tmp/make_vdb_compression_fixtures && /tmp/make_vdb_compression_fixtures tests/data

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT_DIRECTORY\n", argv[0]);
        return 2;
    }
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    openvdb::FloatGrid::Accessor acc = grid->getAccessor();
    for (int k = 5; k <= 7; ++k) {
        for (int j = -2; j <= 1; ++j) {
            for (int i = 3; i <= 7; ++i) {
                const int a = i - 3, b = j + 2, c = k - 5;
                acc.setValueOn(openvdb::Coord(i, j, k), float(0.1 * (a + 2 * b + 3 * c) + 1.0));
            }
        }
    }
    acc.setValueOff(openvdb::Coord(5, -1, 6), 9.0f);
    openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(0.5);
    xform->postTranslate(openvdb::Vec3d(1.0, -2.0, 0.25));
    grid->setTransform(xform);

    const struct { const char* name; uint32_t compression; } files[] = {
        {"vdb_zip.vdb", openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK},
        {"vdb_uncompressed.vdb", openvdb::io::COMPRESS_ACTIVE_MASK},
    };
    for (const auto& f : files) {
        const std::string path = std::string(argv[1]) + "/" + f.name;
        openvdb::io::File file(path);
        file.setCompression(f.compression);
        file.write(openvdb::GridCPtrVec{grid});
        file.close();
        std::printf("%s: %s\n", path.c_str(), xform->mapType().c_str());
    }
    return 0;
}
