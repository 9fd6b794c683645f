// SPDX-License-Identifier: AGPL-3.0-or-later
// The whole job through the C++ API: decorate BASE with SWATCH, write the result with one OBJ
// group per element, print the quality report.
//
//   decorate_example BASE SWATCH OUT.obj [SCALE] [SEED]

#include <meshquilt/meshquilt.h>

#include <cstdio>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: " << argv[0] << " BASE SWATCH OUT.obj [SCALE] [SEED]\n";
        return 2;
    }
    try {
        const meshquilt::Mesh base = meshquilt::read_mesh(argv[1]);
        const meshquilt::Mesh swatch = meshquilt::read_mesh(argv[2]);

        meshquilt::DecorateOptions options;
        options.base_name = argv[1];  // error messages name the inputs
        options.swatch_name = argv[2];
        if (argc > 4) options.surface.scale = std::stod(argv[4]);
        if (argc > 5) options.surface.seed = std::stoull(argv[5]);
        // Progress on stderr; returning false would cancel (decorate then throws Cancelled).
        options.surface.reporter.progress = [](const std::string& stage, double fraction) {
            std::fprintf(stderr, "\r%-10s %3.0f%%", stage.c_str(), 100.0 * fraction);
            return true;
        };
        options.surface.reporter.log = [](meshquilt::LogLevel level, const std::string& text) {
            if (level == meshquilt::LogLevel::Warning) std::cerr << "\nwarning: " << text << '\n';
        };

        const meshquilt::DecorateResult result = meshquilt::decorate(base, swatch, options);
        std::cerr << '\n';
        for (const std::string& w : result.warnings) std::cerr << "warning: " << w << '\n';

        meshquilt::WriteOptions write;
        write.element_of_face = result.decoration.element_of_face;
        meshquilt::write_mesh(argv[3], result.decoration.mesh, write);
        std::cout << "meshquilt " << meshquilt::version() << ": " << result.decoration.num_elements << " elements, "
                  << result.decoration.mesh.num_faces() << " faces, " << result.report.elements_closed << " closed -> " << argv[3]
                  << '\n'
                  << meshquilt::report_json(result);
        return 0;
    } catch (const meshquilt::Error& e) {
        std::cerr << "error: " << e.what() << '\n';
        return meshquilt::exit_code_for(e.code());
    }
}
