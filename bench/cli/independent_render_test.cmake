# Two renderers written apart agree: markerbench's (exact areas) and
# scripts/independent_render.py's (8x8 point samples a pixel, OpenCV's blur), on noise-free
# frames of circles_a (RGB) and circle_d (grey), sharp and blurred (by 0.6 px, where a kernel
# sampled at whole pixels would be 15 levels off, and by 2 px). Sampling places an edge crossing
# a pixel to 1/8 px, so a sharp frame's pixel may differ by up to 255/8 levels, a blurred one by
# 1/16 px times the edge's steepest slope, 255 (2Φ(1/2σ) - 1): 9.5 levels at σ 0.6, 3.1 at 2;
# a half-pixel shift or a wrong colour would differ by many more. The same frames written through
# a camera's response (render.gamma 2.2, v -> v^(1/2.2)) agree as well: a sharp pixel's 1/8 px
# becomes up to 255 (1/8)^(1/2.2) = 99 levels where the response is steepest, at black; the
# blurred frames are held to the linear limits, the response steepening their differences only
# near black, where a blurred edge's slope has faded (measured: at most 6 and 1 levels).
# Run by ctest as bench/independent_render.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# Renders the frames with `render` (a scenario's render: line, or nothing) and compares them;
# a sharp frame may differ by up to `sharp_largest` levels in a pixel.
function(compare_renderers name render sharp_largest)
  file(WRITE ${WORK_DIR}/${name}.yaml "name: ${name}
camera: ${SOURCE_DIR}/scenarios/cameras/default.yaml
markers:
  - ${SOURCE_DIR}/scenarios/markers/circles_a.yaml
  - ${SOURCE_DIR}/scenarios/markers/circle_d.yaml
equal_ink_area_m2: 0.01
trackers:
  - {name: circle}
poses: {sampler: look_at, distance_m: 0.6, tilt_deg: [0, 60], azimuth_deg: [0, 360],
        roll_deg: [0, 360], max_offset_px: 100}
${render}sweep: {parameter: blur_sigma_px, values: [0, 0.6, 2]}
trials: 3
seed: 21
")
  execute_process(COMMAND ${MARKERBENCH} render ${WORK_DIR}/${name}.yaml --out ${WORK_DIR}/${name}
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "render: ${err}")
  endif()
  execute_process(COMMAND ${PYTHON} ${SOURCE_DIR}/scripts/independent_render.py
                          --compare ${WORK_DIR}/${name}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "independent_render.py --compare: ${err}")
  endif()
  string(STRIP "${out}" out)
  string(REPLACE "\n" ";" lines "${out}")
  list(LENGTH lines n)
  if(NOT n EQUAL 18)
    message(FATAL_ERROR "${name}: expected 18 frames compared (2 markers, 3 blurs, 3 trials):\n${out}")
  endif()
  foreach(line IN LISTS lines)
    string(REPLACE " " ";" fields "${line}")
    list(GET fields 1 blur)
    list(GET fields 2 largest)
    list(GET fields 3 mean)
    if(blur EQUAL 0)
      set(max_largest ${sharp_largest})
      set(max_mean 0.01)
    elseif(blur STREQUAL "0.6")
      set(max_largest 10)
      set(max_mean 0.005)
    else()
      set(max_largest 3)
      set(max_mean 0.005)
    endif()
    if(largest GREATER max_largest OR mean GREATER max_mean)
      message(FATAL_ERROR "${name}: frame, blur, largest and mean difference '${line}': allowed "
                          "${max_largest} and ${max_mean} levels")
    endif()
    message(STATUS "${name}: frame, blur, largest and mean difference: ${line}")
  endforeach()
endfunction()

compare_renderers(linear "" 32)
compare_renderers(gamma "render: {gamma: 2.2}\n" 99)
