/* The SDS model fuzzer's words for driver.c (compiled with
 * -DFUZZ_WORDS="sds_words.h"): model syntax, actions, muparser operators and
 * functions, and numbers at the edges. */
static const char *const tokens[] = {
    "->", ":", ";", "=", "(", ")", "#", "\n", "\"", "0", "1", "-1", "0.5", "1e308", "-1e308", "1e-308", "nan",
    "inf", "1e999", "0x10", "1/0", "0/0", "phi", "tip", "clock", "K", "radius", "volume", "time", "_pi",
    "&&", "||", "==", "!=", "<=", ">=", "<", ">", "+", "-", "*", "/", "^", "?", "sqrt(", "min(", "log(-1)",
    /* the bytecode compiler's cases: muparser's optimiser patterns, ?:, variadic functions, signs */
    ",", "max(", "sum(", "avg(", "abs(", "sign(", "rint(", "exp(", "atan2(", "_e", "^2", "^3", "^0", "*2*3",
    "/2", "+radius", "-(", "? 1 : 0", "radius*radius", "2*(3*radius+1)", ".5", "2.5e-3", "=", "surface",
    "(((", ")))", " ", "\t", "\r\n", "grad(phi)", "grad(", "toward", "away", "-grad(phi)", "diffusion=",
    "decay=", "start=", "capped=", "capped=2"};
static const char *const words[] = {
    "morphogen ", "timer ", "state ", "const ", "tip ", "rule ", "model ", "set ", "produce ", "grow ",
    "divide ", "reset ", "morphogen phi diffusion=0.1 decay=0\n", "timer clock decay=0.1 start=1\n",
    "state tip = 1\n", "const K = 0.1\n", "tip 1 0 0\n", "gravity = 10\n", "box = 0 0 0 1 1 1\n",
    "rock = \"r.ply\"\n", "rule r1: tip == 1 -> set phi = volume\n", "rule r2: phi > K -> grow 0.1\n",
    "rule r3: radius > 0.3 -> divide toward grad(phi)\n", "rule r4: clock < 0.5 -> reset clock; set tip = 0\n",
    "rule x: 1 -> produce phi 1\n"};
static const char *param_name(void) { return words[below(sizeof words / sizeof words[0])]; }
