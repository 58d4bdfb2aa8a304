/* The grammar fuzzer's words for driver.c (compiled with
 * -DFUZZ_WORDS="lsys_words.h"): grammar syntax, directives, turtle symbols,
 * muparser operators and functions, and numbers at the edges. */
static const char *const tokens[] = {
    "->", "-(0.5)->", "-(", ")->", "<", ">", ":", "(", ")", ",", "[", "]", "%", "#", "!", "\n",
    "0", "1", "-1", "2.5", "1e308", "-1e308", "1e-308", "nan", "inf", "1e999", "0x10", "1/0", "0/0",
    "x", "y", "n", "x+1", "x*2", "x/0", "x^x", "sqrt(x)", "min(x,1)", "uniform(0,1)", "x>1?1:0",
    "&&", "||", "==", "!=", "<=", ">=", "_pi", "_e", "sin(", "log(", "(((", ")))", " ", "\t", "\r\n",
    "F", "f", "+", "-", "&", "^", "/", "\\", "|", "A(x)", "B(x,y)", "F(1,0.5)", "!(w)", "#(2)"};
static const char *const words[] = {
    "axiom: ", "iterations: ", "angle: ", "width_factor: ", "ignore: ", "define a = ", "define ",
    "A -> ", "A(x) : x > 0 -> ", "A < B > C -> ", "A(x) < B(y) -> ", "# comment", " # c\n", "-(0.3)-> ",
    "axiom: A\n", "A -> F[+A][-A]\n", "iterations: 30\n", "define x = 1\n", "A -> AA\n", "homomorphism:\n"};
static const char *param_name(void) { return words[below(sizeof words / sizeof words[0])]; }
