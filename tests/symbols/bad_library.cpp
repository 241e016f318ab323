// A deliberately leaky shared library for symbols.check_rejects_a_leaky_library: a symbol outside
// namespace sao and a global gl* function.
namespace sao {
int fine() { return 1; }
}  // namespace sao
namespace other {
int helper() { return 2; }
}  // namespace other
extern "C" void glFancy() {}
