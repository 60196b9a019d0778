# The article's printed formulas, for the tests that show a correct stage must not follow
# them (docs/errata.md). Each is the stage's integrator with one corrected line replaced by
# what the article prints, written into the build as printed/NAME.glsl; the stage's own
# source carries no switch for it. Configuring fails if the corrected line is not found
# exactly once, so the printed version cannot silently drift from the stage.
# pt_printed_formula(NAME STAGE CORRECTED PRINTED)
function(pt_printed_formula NAME STAGE CORRECTED PRINTED)
  set(source ${PROJECT_SOURCE_DIR}/${STAGE}/integrator.glsl)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${source})
  file(READ ${source} text)
  string(FIND "${text}" "${CORRECTED}" first)
  string(FIND "${text}" "${CORRECTED}" last REVERSE)
  if(first EQUAL -1 OR NOT first EQUAL last)
    message(FATAL_ERROR "tests/printed_formulas.cmake: '${CORRECTED}' is not in ${STAGE}/integrator.glsl exactly once; "
                        "update the printed formula ${NAME} to the stage's code")
  endif()
  string(REPLACE "${CORRECTED}" "${PRINTED}" text "${text}")
  file(CONFIGURE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/printed/${NAME}.glsl CONTENT
       "// Written by tests/printed_formulas.cmake: ${STAGE}/integrator.glsl with ${NAME} as printed.\n${text}")
endfunction()

# Erratum 1: Eq. (3)'s factor as printed, 1 / (2 pi N), instead of 2 pi / N (N = 1).
pt_printed_formula(stage2_eq3 stage2_montecarlo
  "beta *= uniform_lobe_weight(lobe, eval_lobe(lobe, material, wo, wi), wi);"
  "beta *= (1.0f / (2.0f * kPi)) * eval_lobe(lobe, material, wo, wi) * wi.z;")
# Erratum 2: Eq. (4) as printed, the factor 1 / (2 pi) and no division by the pdf.
pt_printed_formula(stage3_eq4 stage3_importance
  "lobe_cos(lobe, s.wi) / s.pdf;"
  "lobe_cos(lobe, s.wi) / (2.0f * kPi);")
# Erratum 5: Eq. (5) as printed, f Le cos_x: no geometry term cos_y / d^2, no area pdf.
pt_printed_formula(stage4_eq5 stage4_direct_indirect
  "L += beta * b.f * ls.weight * b.cos;"
  "L += beta * b.f * ls.weight * ls.pdf * b.cos;")
