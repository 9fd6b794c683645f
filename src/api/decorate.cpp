// SPDX-License-Identifier: AGPL-3.0-or-later
// decorate(): the whole job (validate, quilt the surface, optionally prepare a print).

#include "meshquilt/decorate.h"

#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "meshquilt/report.h"
#include "meshquilt/version.h"

#include <chrono>
#include <nlohmann/json.hpp>

namespace meshquilt {

const char* version() { return MESHQUILT_VERSION; }

namespace {
/// Keeps a warning in the result and sends it to the reporter's log as it happens.
void warn(DecorateResult& out, const Reporter& reporter, std::string text) {
    reporter.warn(text);
    out.warnings.push_back(std::move(text));
}

Mesh checked(const Mesh& mesh, const std::string& name, bool repair, bool swatch, const Reporter& reporter, DecorateResult& out) {
    ValidationOptions vo;
    vo.repair = repair;
    vo.reorient = !swatch;  // a base's faces are reoriented on the synthesis's copy, with a warning
    vo.require_thin_axis = swatch;
    ValidationResult v = validate(mesh, name, vo);
    for (auto& r : v.repairs) out.repairs.push_back(std::move(r));  // each starts with the file's name
    for (auto& w : v.warnings) warn(out, reporter, std::move(w));
    return std::move(v.mesh);
}
}  // namespace

DecorateResult decorate(const Mesh& base_in, const Mesh& swatch_in, const DecorateOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    DecorateResult out;
    const Reporter& reporter = options.surface.reporter;
    out.base = checked(base_in, options.base_name, options.repair, false, reporter, out);
    const Mesh& base = out.base;
    const Mesh swatch = checked(swatch_in, options.swatch_name, options.repair, true, reporter, out);
    SurfaceQuiltResult r;
    try {
        r = quilt_surface(base, swatch, options.surface);
    } catch (const InvalidInput& e) {
        throw InvalidInput(options.base_name + " + " + options.swatch_name + ": " + e.what());
    }
    out.decoration.mesh = std::move(r.mesh);
    out.decoration.element_of_face = std::move(r.element_of_face);
    out.decoration.num_elements = r.report.elements;
    out.source_element = std::move(r.source_element);
    out.report = std::move(r.report);
    out.surface = std::move(r.surface);
    for (auto& w : r.warnings) warn(out, reporter, std::move(w));
    reporter.info("decorated " + options.base_name + ": " + std::to_string(out.decoration.num_elements) + " elements, " +
                  std::to_string(out.decoration.mesh.num_faces()) + " faces");
    if (options.print) {
        PrintOptions po = *options.print;
        if (!po.reporter.progress && !po.reporter.log) po.reporter = options.surface.reporter;
        // Fused: the decoration and its base make one solid. Separate (print-in-place): the
        // elements alone; the base is the form they were grown on.
        const Mesh* print_base = po.mode == PrintMode::Fused ? &base : nullptr;
        out.print = prepare_print(out.decoration.mesh, print_base, po, options.base_name + " + " + options.swatch_name);
        for (const auto& w : out.print->warnings) warn(out, reporter, "print: " + w);
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

std::string report_json(const DecorateResult& result) {
    std::string text = report_json(result.report, result.surface, result.seconds);
    if (!result.print) return text;
    nlohmann::json j = nlohmann::json::parse(text);
    j["print"] = nlohmann::json::parse(report_json(result.print->report));
    return j.dump(2) + "\n";
}

}  // namespace meshquilt
