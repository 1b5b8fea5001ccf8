# The frame fuzzer (FrameFuzzer.cpp, docs/fuzzing.md): encore_fuzz_numbers' mutations
# (NumberMutator.cpp) through load, Renderer::prepare and one frame on the Vulkan adapter.
# Included by tests/CMakeLists.txt: it is built by the project's compiler (g++) with the GPU
# libraries, which the clang fuzz tree cannot compile. Its seeds are the libFuzzer targets'
# (make-corpus.sh), whose generator is built here too, with g++ like in the fuzz tree.
add_executable(encore_frame_fuzzer ${PROJECT_SOURCE_DIR}/fuzz/FrameFuzzer.cpp
               ${PROJECT_SOURCE_DIR}/fuzz/NumberMutator.cpp ${PROJECT_SOURCE_DIR}/fuzz/NumberMutator.h)
target_link_libraries(encore_frame_fuzzer PRIVATE encore_render encore_scene encore_gpu
                      encore_image encore_core encore_internal_headers nlohmann_json::nlohmann_json)
target_compile_options(encore_frame_fuzzer PRIVATE -Wall -Wextra)

add_executable(encore_fuzz_corpus_generator ${PROJECT_SOURCE_DIR}/fuzz/CorpusGenerator.cpp)
target_link_libraries(encore_fuzz_corpus_generator PRIVATE encore_test_support)

# A short run in the sanitizer build (make test-sanitize, label sanitize): 1,000 inputs, of which
# 285 reach a frame, in about 40 s on two cores (29 s of CPU). `make fuzz-frame` runs it long.
# The seeds are assembled first (a CTest fixture).
if(ENCORE_SANITIZE)
    set(frame_fuzz_seeds ${CMAKE_CURRENT_BINARY_DIR}/frame-fuzz/seeds)
    add_test(NAME encore_frame_fuzz_seeds
        COMMAND bash ${PROJECT_SOURCE_DIR}/fuzz/make-corpus.sh ${frame_fuzz_seeds}
                $<TARGET_FILE:encore_fuzz_corpus_generator> ${ENCORE_SHARED_MODELS_DIR}
                $<TARGET_FILE:encore>)
    set_tests_properties(encore_frame_fuzz_seeds PROPERTIES
        FIXTURES_SETUP frame_fuzz_seeds LABELS sanitize ENVIRONMENT "XDG_RUNTIME_DIR=/tmp")
    add_test(NAME encore_frame_fuzz
        COMMAND encore_frame_fuzzer --iterations 1000 --seed 1
                --findings ${CMAKE_CURRENT_BINARY_DIR}/frame-fuzz/findings ${frame_fuzz_seeds})
    set_tests_properties(encore_frame_fuzz PROPERTIES
        FIXTURES_REQUIRED frame_fuzz_seeds LABELS "gpu;sanitize"
        ENVIRONMENT "XDG_RUNTIME_DIR=/tmp")
    set_property(GLOBAL APPEND PROPERTY ENCORE_SANITIZE_SUITES encore_frame_fuzzer
                 encore_fuzz_corpus_generator encore)
endif()
