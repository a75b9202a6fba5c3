# LSC_ANALYZE: clang-tidy and cppcheck run on every C source the build
# compiles (library, programs, tests, fuzz harnesses); any finding fails the
# build. The check lists are documented in SECURITY.md ("Static analysis").
#  - clang-tidy: the checks of .clang-tidy at the top of the tree, all errors.
#  - cppcheck: warning, style, performance and portability checks; inline
#    suppressions only, each with its reason next to it.
find_program(LSC_CLANG_TIDY NAMES clang-tidy clang-tidy-14 REQUIRED)
find_program(LSC_CPPCHECK NAMES cppcheck REQUIRED)
set(CMAKE_C_CLANG_TIDY ${LSC_CLANG_TIDY} --quiet)
set(CMAKE_C_CPPCHECK ${LSC_CPPCHECK}
    --enable=warning,style,performance,portability
    --std=c99 --inline-suppr --quiet --error-exitcode=1
    --suppress=missingIncludeSystem
    --suppress=unmatchedSuppression)
