#!/bin/sh
# have_fuzzer.sh CC -- exit 0 if CC links a libFuzzer target (clang
# -fsanitize=fuzzer, with address and undefined); used by make fuzz.
cc=${1:-clang}
command -v "$cc" > /dev/null 2>&1 || exit 1
d=$(mktemp -d /tmp/tilesim-fuzz.XXXXXX) || exit 1
printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n);\nint LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }\n' > "$d/t.c"
"$cc" -fsanitize=fuzzer,address,undefined "$d/t.c" -o "$d/t" > /dev/null 2>&1
rc=$?
rm -rf "$d"
exit $rc
