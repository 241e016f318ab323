// The translation unit that compiles tests/CMakeLists.txt's shared precompiled header (GoogleTest
// and the standard headers every test reads); it defines nothing.
