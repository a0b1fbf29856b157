# tilesim -- one Makefile.  Sources are found by wildcard: a new file needs no edit.
#
#   make                 ./tile and ./bench (optimised)
#   make check           every test, built with -Werror and ASan+UBSan
#   make bench           the paper's experiments: CSV and SVG under plots/
#   make bench-tile      the tiler's speed and memory figures
#   make bench-testbed   a user's program's ring beside ./bench --ring: the library's cost
#   make bench-mpi       MPI programs under tilesim-mpirun beside SimGrid's smpirun
#   make bench-load      the threads (and MPI) backends beside busy loops
#   make bench-cores     what depends on the cores, measured here in BUDGET s
#   make valgrind        the tests under valgrind, without sanitizers
#   make tsan            the threads backend's tests under ThreadSanitizer
#   make fuzz            each reader's libFuzzer target for FUZZ_TIME s (clang)
#   make mpi             ./tile-mpi and ./bench-mpi with mpicc (mpirun -np P ...)
#   make simgrid         the simulator against SimGrid's SMPI (tests/simgrid.sh)
#   make install PREFIX=/usr/local   (tile, tilesim-bench, tilesim-plot, man pages)
#   make uninstall PREFIX=/usr/local (every file make install wrote)
#   make clean

CC      ?= cc
PREFIX  ?= /usr/local
CFLAGS  ?= -O3 -g
WARN     = -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes
# -ffp-contract=off: no fused multiply-add, so every build of a tile weight
# rounds the same way (the solver's exactness rests on it).  -I. alone:
# every file names the tree's headers from the root ("sim/link.h"), so that
# no folder of ours shadows a system header (<link.h>, <threads.h>).
BASE     = -std=c11 -D_POSIX_C_SOURCE=200809L -ffp-contract=off -fno-math-errno \
           -I. $(WARN)
LDLIBS   = -lm -pthread
SAN      = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
CHKFLAGS = -O1 -g -Werror $(SAN)

# Library sources: every .c under these folders except the MPI backend,
# which only mpicc can build (make mpi).
LIBDIRS  = util mp sim machine geom algo input surface
LIBSRC   = $(filter-out %mpi.c,$(wildcard $(addsuffix /*.c,$(LIBDIRS))))
# The MPI build (make mpi): every library source, the MPI backend included,
# and tile and bench from their usual sources, by $(MPICC) with -DTILESIM_MPI
# into $(MPIDIR).  Not sanitized; warnings as everywhere.  make check runs
# the MPI tests when $(MPICC) builds an MPI program (mpi-probe, below).
MPICC   ?= mpicc
MPIRUN  ?= mpirun
SMPICC  ?= smpicc
SMPIRUN ?= smpirun
MPIDIR  ?= build/mpi
MPIFLAGS = -O2 -g -DTILESIM_MPI
MPISRC   = $(wildcard $(addsuffix /*.c,$(LIBDIRS)))
MPIPROGS = tile bench
# Programs: prog/NAME.c holds main, prog/NAME_*.c are linked into NAME only;
# or, for a program of many files, prog/NAME/ holds them all (progsrc).
# The MPI tools (tilesim-mpicc, tilesim-mpirun) are built apart, below.
MPITOOLS = tilesim-mpicc tilesim-mpicxx tilesim-mpirun
PROGS    = $(filter-out $(MPITOOLS),$(basename $(notdir $(filter-out $(wildcard prog/*_*.c),$(wildcard prog/*.c))))) \
           $(filter-out plot,$(patsubst prog/%/,%,$(sort $(dir $(wildcard prog/*/*.c)))))
progsrc  = $(wildcard prog/$(1).c prog/$(1)_*.c prog/$(1)/*.c)
# The SVG plotter, prog/plot/*.c, builds to build/plot (plots/ holds what it draws).
PLOTSRC  = $(wildcard prog/plot/*.c)
PLOT     = $(if $(PLOTSRC),build/plot)
TESTS    = $(basename $(notdir $(wildcard tests/test_*.c)))
# The testbed's library for users' own programs (machine/tilesim.h, issue
# 18): util, mp, sim and machine linked into one object whose only global
# symbols are tilesim_* and mp_*, so that a program's own names (xmalloc,
# trace_new, ...) never meet ours; its headers as installed, under
# build/include/tilesim/; and the examples, built against both as a user
# builds them.
PUBDIRS  = util mp sim machine
PUBSRC   = $(filter-out %mpi.c,$(wildcard $(addsuffix /*.c,$(PUBDIRS))))
PUBHDR   = build/include/tilesim/mp.h build/include/tilesim/tilesim.h
# The installed headers name each other from their own folder: the tree's
# "mp/mp.h" and "mpi/mpi_funcs.h" become "mp.h" and "mpi_funcs.h" there.
INSTHDR  = sed -e 's|^\(.include "\)mpi*/|\1|'
OBJCOPY ?= objcopy
EXAMPLES = $(basename $(notdir $(wildcard examples/*.c)))
EXFLAGS  = -std=c11 $(WARN) -Ibuild/include
TESTLIB  = $(filter-out $(wildcard tests/test_*.c),$(wildcard tests/*.c))

# The MPI layer (mpi/): every mpi/*.c into libtsmpi.a.  Its files
# name it "mpi/mpi.h", so that every other file's <mpi.h> stays the real
# MPI's (make mpi).  The MPI programs of
# tests/mpi/ (but contract.c, the MPI backend's, which only mpicc builds) are
# built against it with -Impi and their main renamed tsmpi_main_NAME, and
# run on the simulator by tests/test_mpiprogs.c (and under Open MPI by
# tests/cli_mpiprogs.sh).
TSMPISRC   = $(wildcard mpi/*.c)
TSMPIPROGS = $(basename $(notdir $(filter-out tests/mpi/contract.c,$(wildcard tests/mpi/*.c))))
TSMPIPFLAGS = -Impi -Wno-missing-prototypes
# The runner's own (mpirun/*.c: each rank's libc and C++ runtime, the
# compute modes, the loader, crashes, the ELF reader, the compiler wrapper)
# into libtsmpirun.a; tilesim-mpirun exports to the programs it loads only
# what they may call (mpirun/exports.list: MPI_*, PMPI_*, tilesim_compute,
# smpi_*).  mpirun/stublib.c is apart: the library programs link against
# (STUBLIB, below).
RUNSRC     = $(filter-out mpirun/stublib.c,$(wildcard mpirun/*.c))
MPIHDR     = build/include/tilesim/mpi/mpi.h build/include/tilesim/mpi/mpi_funcs.h
STUBLIB    = build/lib/tilesim/libtilesim_mpi.so
RUNLDFLAGS = -Wl,--dynamic-list=mpirun/exports.list
RUNLIBS    = -ldl

REL = build/rel
CHK = build/chk
relobj = $(patsubst %.c,$(REL)/%.o,$(1))
chkobj = $(patsubst %.c,$(CHK)/%.o,$(1))

# Programs build into build/bin and are copied to the root when they change,
# so that `make bench` can be the experiments rather than the program.
all: $(addprefix build/bin/,$(PROGS) $(MPITOOLS)) $(PLOT) $(REL)/lib/libtilesim.a \
     $(addprefix build/examples/,$(EXAMPLES)) $(REL)/libtsmpi.a $(MPIHDR) $(STUBLIB)
	@for p in $(PROGS) $(MPITOOLS); do cmp -s build/bin/$$p $$p || cp -f build/bin/$$p $$p; done

$(REL)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(BASE) $(CFLAGS) -MMD -MP -c $< -o $@

$(CHK)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(BASE) $(CHKFLAGS) -MMD -MP -c $< -o $@

# Every archive: rebuilt whole from its objects, the prerequisites each
# library's line below names.
%.a:
	@rm -f $@
	$(AR) rcs $@ $^

$(REL)/libtilesim.a: $(call relobj,$(LIBSRC))

$(CHK)/libtilesim.a: $(call chkobj,$(LIBSRC))

build/include/tilesim/mp.h: mp/mp.h
build/include/tilesim/tilesim.h: machine/tilesim.h
build/include/tilesim/mp.h build/include/tilesim/tilesim.h:
	@mkdir -p $(dir $@)
	$(INSTHDR) $< > $@
# tilesim-mpicc's headers, as installed: include/tilesim/mpi/ (MPIHDR, above).
build/include/tilesim/mpi/%.h: mpi/%.h
	@mkdir -p $(dir $@)
	$(INSTHDR) $< > $@
# The library every program tilesim-mpicc links is linked against: each
# name tilesim-mpirun provides, and the word for a program run on its own
# (mpirun/stublib.c); the predefined callbacks are mpi/callbacks.c's.
$(STUBLIB): mpirun/stublib.c mpi/callbacks.c mpi/mpi.h mpi/mpi_funcs.h mpi/io_sg.h
	@mkdir -p $(dir $@)
	$(CC) $(BASE) $(CFLAGS) -fPIC -shared -Wl,-soname,libtilesim_mpi.so -o $@ mpirun/stublib.c \
	  mpi/callbacks.c

# The runner's library.
$(REL)/libtsmpirun.a: $(call relobj,$(RUNSRC))
$(CHK)/libtsmpirun.a: $(call chkobj,$(RUNSRC))
# tilesim-mpirun: every object of the two MPI libraries (a program may call
# any of them), exported; tilesim-mpicc: the list of functions and the ELF reader.
define mpitool_rules
build/bin/tilesim-mpirun: $(REL)/prog/tilesim-mpirun.o $(REL)/libtsmpirun.a $(REL)/libtsmpi.a $(REL)/libtilesim.a
	@mkdir -p build/bin
	$$(CC) $$(CFLAGS) $$(RUNLDFLAGS) -o $$@ $$< -Wl,--whole-archive $(REL)/libtsmpirun.a $(REL)/libtsmpi.a \
	  -Wl,--no-whole-archive $(REL)/libtilesim.a $$(LDLIBS) $$(RUNLIBS)
$(CHK)/tilesim-mpirun: $(CHK)/prog/tilesim-mpirun.o $(CHK)/libtsmpirun.a $(CHK)/libtsmpi.a $(CHK)/libtilesim.a
	$$(CC) $$(CHKFLAGS) $$(RUNLDFLAGS) -o $$@ $$< -Wl,--whole-archive $(CHK)/libtsmpirun.a $(CHK)/libtsmpi.a \
	  -Wl,--no-whole-archive $(CHK)/libtilesim.a $$(LDLIBS) $$(RUNLIBS)
build/bin/tilesim-mpic%: $(REL)/prog/tilesim-mpic%.o $(REL)/libtsmpirun.a $(REL)/libtsmpi.a $(REL)/libtilesim.a
	@mkdir -p build/bin
	$$(CC) $$(CFLAGS) -o $$@ $$^ $$(LDLIBS) $$(RUNLIBS)
$(CHK)/tilesim-mpic%: $(CHK)/prog/tilesim-mpic%.o $(CHK)/libtsmpirun.a $(CHK)/libtsmpi.a $(CHK)/libtilesim.a
	$$(CC) $$(CHKFLAGS) -o $$@ $$^ $$(LDLIBS) $$(RUNLIBS)
endef
$(eval $(mpitool_rules))
# bench --calibrate's basic blocks: this loop compiled as tilesim-mpicc
# --count-blocks compiles programs.
$(REL)/prog/bench/blocks.o: CFLAGS += -fsanitize-coverage=trace-pc
$(CHK)/prog/bench/blocks.o: CHKFLAGS += -fsanitize-coverage=trace-pc
# publib(DIR,SOURCES): DIR/lib/libtilesim.a from the sources' objects in DIR.
define publib
$(1)/lib/libtilesim.a: $(patsubst %.c,$(1)/%.o,$(2))
	@mkdir -p $(1)/lib
	$$(CC) -r -nostdlib -o $(1)/lib/tilesim.o $$^
	$$(OBJCOPY) --wildcard -G 'tilesim_*' -G 'mp_*' $(1)/lib/tilesim.o
	@rm -f $$@
	$$(AR) rcs $$@ $(1)/lib/tilesim.o
endef
$(eval $(call publib,$(REL),$(PUBSRC)))
$(eval $(call publib,$(CHK),$(PUBSRC)))
$(eval $(call publib,$(MPIDIR),$(wildcard $(addsuffix /*.c,$(PUBDIRS)))))
build/examples/%: examples/%.c $(REL)/lib/libtilesim.a $(PUBHDR)
	@mkdir -p build/examples
	$(CC) $(EXFLAGS) $(CFLAGS) -o $@ $< $(REL)/lib/libtilesim.a $(LDLIBS)
$(CHK)/examples/%: examples/%.c $(CHK)/lib/libtilesim.a $(PUBHDR)
	@mkdir -p $(CHK)/examples
	$(CC) $(EXFLAGS) $(CHKFLAGS) -o $@ $< $(CHK)/lib/libtilesim.a $(LDLIBS)
# Users' programs the testbed's tests run (tests/testbed/*.c), built the same way.
TESTBED = $(basename $(notdir $(wildcard tests/testbed/*.c)))
$(CHK)/testbed/%: tests/testbed/%.c $(CHK)/lib/libtilesim.a $(PUBHDR)
	@mkdir -p $(CHK)/testbed
	$(CC) $(EXFLAGS) $(CHKFLAGS) -o $@ $< $(CHK)/lib/libtilesim.a $(LDLIBS)

$(REL)/libtsmpi.a: $(call relobj,$(TSMPISRC))

$(CHK)/libtsmpi.a: $(call chkobj,$(TSMPISRC))

# The MPI test programs: main renamed, tilesim's mpi.h; and their list for
# the driver, rewritten only when it changes.
$(CHK)/tests/mpi/%.o: tests/mpi/%.c
	@mkdir -p $(dir $@)
	$(CC) $(BASE) $(CHKFLAGS) $(TSMPIPFLAGS) -Dmain=tsmpi_main_$* -MMD -MP -c $< -o $@
$(CHK)/tests/mpi/progs.h: FORCE
	@mkdir -p $(dir $@)
	@printf '%s\n' $(foreach p,$(TSMPIPROGS),'TSMPI_PROG($(p))') > $@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv -f $@.tmp $@; fi
# The drivers that link the programs in: test_mpiprogs (datatypes,
# operations, collectives) and test_mpiprogs_p2p (point-to-point and
# communicators).
TSMPIDRIVERS = test_mpiprogs test_mpiprogs_p2p
define tsmpi_driver_rules
$(CHK)/tests/$(1).o: $(CHK)/tests/mpi/progs.h
$(CHK)/tests/$(1).o: CHKFLAGS += -I$(CHK)/tests/mpi
$(CHK)/tests/$(1): $(CHK)/tests/$(1).o $(patsubst %,$(CHK)/tests/mpi/%.o,$(TSMPIPROGS)) \
                   $(call chkobj,$(TESTLIB)) $(CHK)/libtsmpi.a $(CHK)/libtilesim.a
	$$(CC) $$(CHKFLAGS) -o $$@ $$^ $$(LDLIBS)
$(VG)/tests/$(1).o: $(CHK)/tests/mpi/progs.h
$(VG)/tests/$(1).o: BASE += -I$(CHK)/tests/mpi
$(VG)/tests/$(1): $(VG)/tests/$(1).o $(patsubst %,$(VG)/tests/mpi/%.o,$(TSMPIPROGS)) \
                  $(patsubst %.c,$(VG)/%.o,$(TESTLIB)) $(VG)/libtsmpi.a $(VG)/libtilesim.a
	$$(CC) -g -o $$@ $$^ $$(LDLIBS)
endef

define prog_rules
build/bin/$(1): $(call relobj,$(call progsrc,$(1))) $(REL)/libtilesim.a
	@mkdir -p build/bin
	$$(CC) $$(CFLAGS) -o $$@ $$^ $$(LDLIBS)
$(CHK)/$(1): $(call chkobj,$(call progsrc,$(1))) $(CHK)/libtilesim.a
	$$(CC) $$(CHKFLAGS) -o $$@ $$^ $$(LDLIBS)
endef
$(foreach p,$(PROGS),$(eval $(call prog_rules,$(p))))

build/plot: $(call relobj,$(PLOTSRC)) $(REL)/libtilesim.a
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)
$(CHK)/plot: $(call chkobj,$(PLOTSRC)) $(CHK)/libtilesim.a
	$(CC) $(CHKFLAGS) -o $@ $^ $(LDLIBS)

$(CHK)/tests/%: $(CHK)/tests/%.o $(call chkobj,$(TESTLIB)) $(CHK)/libtsmpi.a $(CHK)/libtilesim.a
	$(CC) $(CHKFLAGS) -o $@ $^ $(LDLIBS)
# The plotter's charts, tested apart from the plotter's main.
$(CHK)/tests/test_svgchart: $(CHK)/tests/test_svgchart.o $(CHK)/prog/plot/svgchart.o $(call chkobj,$(TESTLIB)) \
                            $(CHK)/libtsmpi.a $(CHK)/libtilesim.a
	$(CC) $(CHKFLAGS) -o $@ $^ $(LDLIBS)

# The tests and the sanitized programs the command-line tests drive; and,
# where $(MPICC) (and $(SMPICC)) build an MPI program, the MPI programs for
# tests/cli_mpi.sh (tests/cli_simgrid.sh).  The probe's answers, "yes" or
# why not, reach the tests as MPI_STATUS and SMPI_STATUS (with MPICC,
# MPIRUN, SMPICC, SMPIRUN): they look for nothing themselves, and
# tests/run.sh lists what was skipped and why before its last line.
check: $(addprefix $(CHK)/tests/,$(TESTS)) $(addprefix $(CHK)/,$(PROGS)) $(if $(PLOTSRC),$(CHK)/plot) \
       $(addprefix $(CHK)/examples/,$(EXAMPLES)) $(addprefix $(CHK)/testbed/,$(TESTBED)) \
       $(addprefix $(CHK)/,$(MPITOOLS)) $(MPIHDR) $(STUBLIB)
	@$(MAKE) --no-print-directory -s mpi-probe
	@mpi=$$(cat $(PROBE)/mpicc); smpi=$$(cat $(PROBE)/smpicc); \
	if [ "$$mpi" = yes ] && ! $(MAKE) --no-print-directory -s mpi-bins; then mpi="the MPI build failed (make mpi-bins)"; fi; \
	if [ "$$smpi" = yes ] && ! $(MAKE) --no-print-directory -s smpi-bins; then smpi="the SimGrid build failed (make smpi-bins)"; fi; \
	MPI_STATUS="$$mpi" SMPI_STATUS="$$smpi" MPICC="$(MPICC)" MPIRUN="$(MPIRUN)" SMPICC="$(SMPICC)" \
	SMPIRUN="$(SMPIRUN)" sh tests/run.sh $(CHK) $(addprefix $(CHK)/tests/,$(TESTS)) $(wildcard tests/cli_*.sh)

# Does an MPI compiler work?  Two lines of C compiled and linked by $(MPICC)
# and by $(SMPICC), once per make check; $(PROBE)/mpicc and $(PROBE)/smpicc
# get "yes", or why not (not found; cannot build, with the compiler's first
# line: an mpicc without mpi.h, as Debian's openmpi-bin without
# libopenmpi-dev; no $(MPIRUN)).
PROBE ?= build/probe
probe = if ! command -v $(1) >/dev/null 2>&1; then echo "$(1) not found"; \
	elif ! $(1) $(PROBE)/probe.c -o $(PROBE)/$(3).out > $(PROBE)/$(3).log 2>&1; then \
	  echo "$(1) cannot build a two-line MPI program: $$(grep -m 1 . $(PROBE)/$(3).log)"; \
	elif ! command -v $(2) >/dev/null 2>&1; then echo "$(2) not found"; \
	else echo yes; fi > $(PROBE)/$(3)
mpi-probe:
	@mkdir -p $(PROBE)
	@printf '#include <mpi.h>\nint main(int c, char **v) { MPI_Init(&c, &v); return MPI_Finalize(); }\n' \
	  > $(PROBE)/probe.c
	@$(call probe,$(MPICC),$(MPIRUN),mpicc)
	@$(call probe,$(SMPICC),$(SMPIRUN),smpicc)

# The MPI programs: build/mpi/bin/NAME-mpi, copied to ./NAME-mpi; and the
# MPI backend's contract test (tests/mpi/contract.c, run by tests/cli_mpi.sh).
$(MPIDIR)/%.o: %.c
	@mkdir -p $(dir $@)
	$(MPICC) $(BASE) $(MPIFLAGS) -MMD -MP -c $< -o $@
$(MPIDIR)/libtilesim.a: $(patsubst %.c,$(MPIDIR)/%.o,$(MPISRC))
define mpi_rules
$(MPIDIR)/bin/$(1)-mpi: $(patsubst %.c,$(MPIDIR)/%.o,$(call progsrc,$(1))) $(MPIDIR)/libtilesim.a
	@mkdir -p $(MPIDIR)/bin
	$$(MPICC) $$(MPIFLAGS) -o $$@ $$^ $$(LDLIBS)
endef
$(foreach p,$(MPIPROGS),$(eval $(call mpi_rules,$(p))))
$(MPIDIR)/bin/contract-mpi: $(MPIDIR)/tests/mpi/contract.o $(MPIDIR)/libtilesim.a
	@mkdir -p $(MPIDIR)/bin
	$(MPICC) $(MPIFLAGS) -o $@ $^ $(LDLIBS)
# The examples on MPI (tests/cli_testbed.sh runs them under mpirun).
$(MPIDIR)/examples/%: examples/%.c $(MPIDIR)/lib/libtilesim.a $(PUBHDR)
	@mkdir -p $(MPIDIR)/examples
	$(MPICC) $(EXFLAGS) $(MPIFLAGS) -o $@ $< $(MPIDIR)/lib/libtilesim.a $(LDLIBS)
mpi-bins: $(foreach p,$(MPIPROGS),$(MPIDIR)/bin/$(p)-mpi) $(MPIDIR)/bin/contract-mpi \
          $(addprefix $(MPIDIR)/examples/,$(EXAMPLES))
mpi: mpi-bins
	@for p in $(MPIPROGS); do cmp -s $(MPIDIR)/bin/$$p-mpi $$p-mpi || cp -f $(MPIDIR)/bin/$$p-mpi $$p-mpi; done

# SimGrid: the same MPI programs built by smpicc into build/smpi, run under
# smpirun against the simulator's ideal network (tests/simgrid.sh says how).
smpi-bins:
	$(MAKE) mpi-bins MPICC=$(SMPICC) MPIDIR=build/smpi
simgrid: all mpi-probe
	@smpi=$$(cat $(PROBE)/smpicc); \
	if [ "$$smpi" = yes ] && ! $(MAKE) --no-print-directory smpi-bins; then smpi="the SimGrid build failed"; fi; \
	SMPI_STATUS="$$smpi" SMPICC="$(SMPICC)" SMPIRUN="$(SMPIRUN)" NOBUILD=1 sh tests/simgrid.sh

# The same tests, built without sanitizers, under valgrind.
VG = build/vg
$(VG)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(BASE) -O1 -g -MMD -MP -c $< -o $@
$(VG)/libtilesim.a: $(patsubst %.c,$(VG)/%.o,$(LIBSRC))
$(VG)/libtsmpi.a: $(patsubst %.c,$(VG)/%.o,$(TSMPISRC))
$(VG)/tests/mpi/%.o: tests/mpi/%.c
	@mkdir -p $(dir $@)
	$(CC) $(BASE) -O1 -g $(TSMPIPFLAGS) -Dmain=tsmpi_main_$* -MMD -MP -c $< -o $@
$(foreach d,$(TSMPIDRIVERS),$(eval $(call tsmpi_driver_rules,$(d))))
$(VG)/tests/%: $(VG)/tests/%.o $(patsubst %.c,$(VG)/%.o,$(TESTLIB)) $(VG)/libtsmpi.a $(VG)/libtilesim.a
	$(CC) -g -o $@ $^ $(LDLIBS)
$(VG)/tests/test_svgchart: $(VG)/tests/test_svgchart.o $(VG)/prog/plot/svgchart.o $(patsubst %.c,$(VG)/%.o,$(TESTLIB)) \
                           $(VG)/libtsmpi.a $(VG)/libtilesim.a
	$(CC) -g -o $@ $^ $(LDLIBS)
valgrind: $(addprefix $(VG)/tests/,$(TESTS))
	@VALGRIND="valgrind -q --error-exitcode=99 --leak-check=full" \
	  sh tests/run.sh $(VG) $(addprefix $(VG)/tests/,$(TESTS))

# The threads backend's tests (TSAN_TESTS) built with ThreadSanitizer by
# $(TSANCC) into $(TSAN) and run; a race report fails the test.  Not part
# of make check (TSan is 5 to 15 times slower, and another full build).
# A long hunt: make tsan TILESIM_STRESS=2000 (tests/test_mpstress.c).
TSANCC    ?= $(CC)
TSAN       = build/tsan
TSANFLAGS  = -O1 -g -fsanitize=thread -fno-omit-frame-pointer
TSAN_TESTS ?= test_mpstress test_threads test_variants test_cpuload test_mpi_match test_mpref
$(TSAN)/%.o: %.c
	@mkdir -p $(dir $@)
	$(TSANCC) $(BASE) $(TSANFLAGS) -Werror -MMD -MP -c $< -o $@
$(TSAN)/libtilesim.a: $(patsubst %.c,$(TSAN)/%.o,$(LIBSRC))
$(TSAN)/libtsmpi.a: $(patsubst %.c,$(TSAN)/%.o,$(TSMPISRC))
$(TSAN)/tests/%: $(TSAN)/tests/%.o $(patsubst %.c,$(TSAN)/%.o,$(TESTLIB)) $(TSAN)/libtsmpi.a $(TSAN)/libtilesim.a
	$(TSANCC) $(TSANFLAGS) -o $@ $^ $(LDLIBS)
tsan: $(addprefix $(TSAN)/tests/,$(TSAN_TESTS))
	@TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1 $${TSAN_OPTIONS:-}" \
	  sh tests/run.sh $(TSAN) $(addprefix $(TSAN)/tests/,$(TSAN_TESTS))

# Fuzzing (clang's libFuzzer): one target per reader, tests/fuzz/fuzz_*.c,
# over tests/pipeline.c (what ./tile does, with invariants that abort), each
# run FUZZ_TIME seconds on a corpus under build/fuzz seeded from
# tests/fuzz/corpus_NAME/ (FUZZ_JOBS parallel jobs; a crash is kept in
# build/fuzz/ and fails the run).  Skipped, and said so, where $(FUZZCC)
# cannot build with -fsanitize=fuzzer (Debian: clang, libclang-rt-dev).
FUZZCC    ?= clang
FUZZ_TIME ?= 15
FUZZ_JOBS ?= 1
FUZZ       = build/fuzz
FUZZFLAGS  = -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZERS    = $(basename $(notdir $(wildcard tests/fuzz/fuzz_*.c)))
$(FUZZ)/%.o: %.c
	@mkdir -p $(dir $@)
	$(FUZZCC) $(BASE) $(FUZZFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@
$(FUZZ)/libtilesim.a: $(patsubst %.c,$(FUZZ)/%.o,$(LIBSRC))
$(FUZZ)/bin/%: $(FUZZ)/tests/fuzz/%.o $(FUZZ)/tests/pipeline.o $(FUZZ)/tests/rtwriter.o $(FUZZ)/libtilesim.a
	@mkdir -p $(FUZZ)/bin
	$(FUZZCC) $(FUZZFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)
fuzz-bins: $(addprefix $(FUZZ)/bin/,$(FUZZERS))
fuzz:
	@if sh tests/fuzz/have_fuzzer.sh $(FUZZCC); then \
	  $(MAKE) fuzz-bins && sh tests/fuzz/run.sh $(FUZZ) $(FUZZ_TIME) $(FUZZ_JOBS) $(FUZZERS); \
	else echo "make fuzz: skipped: $(FUZZCC) cannot build with -fsanitize=fuzzer (install clang and libclang-rt-dev)"; fi

# The main job: the paper's experiments on the simulated machine, as CSV and
# SVG under plots/, and the claims of sections 6 and 7 checked against them.
JOBS ?= 2
PLOTS = build/plot lines
# Host times stay out of the committed files (the sweeps' wall_s column is
# left empty): make bench gives the same bytes on every run, and a fresh
# clone stays clean (tests/cli_benchclean.sh checks it).
NOWALL = --no-wall
# Section 8's question (doc/paper.md, "Section 8"): the bus, and a line,
# a mesh and a hypercube with their dilation-1 placements against a random one.
TOPO = --points 300 --procs 1..16 --jobs $(JOBS) $(NOWALL)
TOPONET = --hop-latency 1e-4 --switching store-and-forward
# The variants beside the paper's algorithm: on the tc2000, and on
# the simulator calibrated to a 16-core Xeon (bench --calibrate there: c, m,
# per_byte of the threads backend; doc/measurements.md, "The variants on 16
# real cores").
VARIANTS = paper,fit,block8,dynamic,dynamic+block8
XEON16 = --net ideal --m 5.453e-07 --c 2.675e-09 --per-byte 1.599e-10
# Where the claims hold (doc/paper.md, "The map"): the generated pair and
# the real pair on the bus, m/c from 1 to 128 at c = 50 us (the coarse grid;
# doc/paper.md gives the fine one).
CLAIMS_GEN = --m 5e-5,1e-4,2e-4,2.75e-4,4e-4,8e-4,1.6e-3,3.2e-3,6.4e-3
CLAIMS_REAL = --input tests/data/slicerrt/prostate_0.contours --pair 40 --m 1e-4,2.75e-4,8e-4,3.2e-3
bench: all
	./bench --alloc half,size --jobs $(JOBS) $(NOWALL) -o plots/speedup.csv
	./bench --points 500 --alloc size --min-diag 20,40,60,80,100 --jobs $(JOBS) $(NOWALL) -o plots/min_diag.csv
	./bench --model -o plots/model.csv
	./bench --glass -o plots/glass.contours
	$(PLOTS) plots/speedup.csv -x procs -y speedup --series points --where alloc=half --yzero \
	  --title "Fig. 16: speedup, half of the processors to each subgraph" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/fig16_speedup_half.svg
	$(PLOTS) plots/speedup.csv -x procs -y speedup --series points --where alloc=size --yzero \
	  --title "Fig. 18/19: speedup, processors by subgraph size" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/fig18_speedup_size.svg
	$(PLOTS) plots/speedup.csv -x procs -y speedup --series alloc --where points=500 --yzero \
	  --title "500 points: half against size allocation" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/fig19_half_vs_size.svg
	$(PLOTS) plots/min_diag.csv -x procs -y sim_time --series min_diag --yzero \
	  --title "Fig. 20: time, 500 points, at least d nodes a diagonal" \
	  --xlabel processors --ylabel "simulated time (s)" -o plots/fig20_time_min_diag.svg
	$(PLOTS) plots/min_diag.csv -x procs -y speedup --series min_diag --yzero \
	  --title "Fig. 21: speedup, 500 points, at least d nodes a diagonal" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/fig21_speedup_min_diag.svg
	$(PLOTS) plots/model.csv -x slaves -y sim_per_diag,model_per_diag --series diag \
	  --labels simulated,model --yzero \
	  --title "Section 7.2: time per diagonal of D nodes; model cD/p + 2m(p-1)" \
	  --xlabel "slaves p" --ylabel "seconds per diagonal" -o plots/model_per_diagonal.svg
	build/plot surface plots/glass.contours --band plain --no-caps \
	  --title "Fig. 17: the contours of a glass, and the surface tilesim derives" -o plots/fig17_glass.svg
	./bench --input tests/data/slicerrt/prostate_0.contours --pair 40 --alloc half,size --jobs $(JOBS) \
	  $(NOWALL) -o plots/real_speedup.csv
	$(PLOTS) plots/real_speedup.csv -x procs -y speedup --series alloc --yzero \
	  --title "A real pair (prostate_0, slices 40-41, 512 and 510 points)" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/real_half_vs_size.svg
	./bench $(TOPO) --topology bus -o build/topology_bus.csv
	./bench $(TOPO) $(TOPONET) --topology line --place linear,random:1 -o build/topology_line.csv
	./bench $(TOPO) $(TOPONET) --topology mesh:4x4 --place snake,random:1 -o build/topology_mesh.csv
	./bench $(TOPO) $(TOPONET) --topology hypercube:4 --place gray,random:1 -o build/topology_cube.csv
	awk 'FNR > 1 || NR == 1' build/topology_bus.csv build/topology_line.csv build/topology_mesh.csv \
	  build/topology_cube.csv > build/topology.csv && mv build/topology.csv plots/topology.csv
	$(PLOTS) plots/topology.csv -x procs -y speedup --series topology,place --yzero \
	  --labels "bus (the paper's),line: linear,line: random,mesh 4x4: snake,mesh 4x4: random,hypercube: Gray,hypercube: random" \
	  --title "Section 8: 300 points on direct networks, 100 us a hop, store-and-forward" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/section8_topology.svg
	./bench --claims plots/real_speedup.csv > build/real_claims.csv && mv build/real_claims.csv plots/real_claims.csv
	./bench --claims plots/speedup.csv plots/min_diag.csv > build/claims.csv && mv build/claims.csv plots/claims.csv
	@cat plots/claims.csv
	./bench --points 500 --variant $(VARIANTS) --jobs $(JOBS) $(NOWALL) -o plots/variants_tc2000.csv
	./bench --points 1000 $(XEON16) --variant $(VARIANTS) --jobs $(JOBS) $(NOWALL) -o plots/variants_xeon16.csv
	awk -F, 'FNR == 1 { for (i = 1; i <= NF; i++) c[$$i] = i; f++; if (f == 1) print "variant,procs,tc2000,xeon16"; next } \
	  { k = $$c["variant"] "," $$c["procs"] } f == 1 { a[k] = $$c["speedup"] } f == 2 && (k in a) { print k "," a[k] "," $$c["speedup"] }' \
	  plots/variants_tc2000.csv plots/variants_xeon16.csv > build/variants.csv && mv build/variants.csv plots/variants.csv
	$(PLOTS) plots/variants.csv -x procs -y tc2000,xeon16 --series variant \
	  --labels "tc2000,16-core host" --yzero \
	  --title "The variants: speedup on the simulated tc2000 (500 points) and on the simulator calibrated to a 16-core host (1000 points)" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/variants.svg
	./bench --claims-map $(CLAIMS_GEN) --jobs $(JOBS) -o build/claims_map_gen.csv
	./bench --claims-map $(CLAIMS_REAL) --jobs $(JOBS) -o build/claims_map_real.csv
	awk 'FNR > 1 || NR == 1' build/claims_map_gen.csv build/claims_map_real.csv > build/claims_map.csv && \
	  mv build/claims_map.csv plots/claims_map.csv
	build/plot claims plots/claims_map.csv -o plots/claims_map.svg
	sh examples/jacobi_speedup.sh build/examples/jacobi > build/testbed_jacobi.csv && \
	  mv build/testbed_jacobi.csv plots/testbed_jacobi.csv
	$(PLOTS) plots/testbed_jacobi.csv -x procs -y speedup --series machine --yzero \
	  --labels "tc2000 (a bus),4x4 torus" \
	  --title "A user's program on the machine: examples/jacobi.c, 256 x 256, 1 us a point" \
	  --xlabel processors --ylabel "speedup T(1)/T(P)" -o plots/testbed_jacobi.svg

# The tiler's speed and memory (issue figures: 500 x 500, 5000 x 5000, the naive
# reference, the whole prostate_0 stack), and how fast an RT structure set is read.
bench-tile: all
	./bench --tiler
	./bench --stack
	./bench --dicom
	./bench --union

# The testbed's cost: a user's ring through tilesim.h beside
# ./bench --ring, the simulator driven directly (tests/bench_testbed.sh).
bench-testbed: all
	sh tests/bench_testbed.sh

# MPI programs under tilesim-mpirun beside SimGrid's smpirun:
# bandwidth, alltoall, a ring, start-up and allreduce by the hundred
# thousand ranks, the mp.h ring on a million; time and peak memory against
# the message size and the ranks, into OUT (default build/bench-mpi:
# bench-mpi.csv, .md, the SVGs).  tests/bench_mpi.sh says what and how; the
# settings go in the environment.  bench-mpirun: its older name.
bench-mpi bench-mpirun: all
	@OUT="$(if $(filter command line environment,$(origin OUT)),$(OUT),build/bench-mpi)" sh tests/bench_mpi.sh

# The threads and MPI backends' waiting under outside load:
# runs alone and beside two busy loops (tests/bench_load.sh says what to set).
bench-load: all
	sh tests/bench_load.sh

# Everything that depends on the number of cores, measured on this machine in
# one command within BUDGET seconds: the threads backend's speedup
# at 2000 and 4000 points (the paper's algorithm and the best variants) beside
# the calibrated simulator's prediction, and ./tile -j N on the largest real
# stacks; cores.csv, cores.md and cores.svg in OUT (doc/bench-cores.md).
BUDGET ?= 480
OUT    ?= build/cores
bench-cores: all
	@BUDGET="$(BUDGET)" OUT="$(OUT)" CC="$(CC)" CFLAGS="$(CFLAGS)" sh tests/bench_cores.sh

# make install: the programs, their manual, and under PREFIX/share/tilesim
# the data that bench's defaults name (tests/data/slicerrt, tests/data/rtstruct,
# with their licences), so that an installed bench runs from any folder.
# Installed names that do not collide with other software: tile, and
# tilesim-bench and tilesim-plot for ./bench and build/plot ("bench" alone is
# a common command).  The man pages (doc/*.1, *.5, *.7, mdoc) go to
# MANDIR/man1, man3 (the library), man5, man7, which man finds when PREFIX/bin is on the PATH;
# doc/*.md to DOCDIR.  The testbed's library: lib/libtilesim.a,
# include/tilesim/{tilesim,mp}.h, lib/pkgconfig/tilesim.pc and the examples'
# sources under share/tilesim/examples.  install-files copies from IBIN,
# IPLOT and ILIB (tests/cli_install.sh installs the sanitized build so).
IBIN   ?= build/bin
IPLOT  ?= build/plot
ILIB   ?= $(REL)/lib/libtilesim.a
VERSION = $(shell sed -n 's/^\#define TILESIM_VERSION "\(.*\)"/\1/p' machine/tilesim.h)
SHARE   = $(DESTDIR)$(PREFIX)/share/tilesim
MANDIR ?= $(PREFIX)/share/man
DOCDIR ?= $(PREFIX)/share/doc/tilesim
INAME_bench = tilesim-bench
iname   = $(or $(INAME_$(1)),$(1))
install: all
	@$(MAKE) --no-print-directory install-files
install-files:
	mkdir -p $(DESTDIR)$(PREFIX)/bin $(SHARE)/slicerrt $(SHARE)/rtstruct $(DESTDIR)$(DOCDIR) \
	  $(addprefix $(DESTDIR)$(MANDIR)/man,1 3 5 7)
	$(foreach p,$(PROGS),cp $(IBIN)/$(p) $(DESTDIR)$(PREFIX)/bin/$(call iname,$(p)) &&) true
	$(if $(PLOT),cp $(IPLOT) $(DESTDIR)$(PREFIX)/bin/tilesim-plot)
	cp $(wildcard doc/*.1) $(DESTDIR)$(MANDIR)/man1/
	cp $(wildcard doc/*.5) $(DESTDIR)$(MANDIR)/man5/
	cp $(wildcard doc/*.3) $(DESTDIR)$(MANDIR)/man3/
	cp $(wildcard doc/*.7) $(DESTDIR)$(MANDIR)/man7/
	cp $(wildcard doc/*.md) $(DESTDIR)$(DOCDIR)/
	cp tests/data/slicerrt/*.contours tests/data/slicerrt/README.md $(SHARE)/slicerrt/
	cp tests/data/rtstruct/*.dcm tests/data/rtstruct/README.md $(SHARE)/rtstruct/
	mkdir -p $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/tilesim $(SHARE)/examples
	cp $(ILIB) $(DESTDIR)$(PREFIX)/lib/libtilesim.a
	$(INSTHDR) mp/mp.h > $(DESTDIR)$(PREFIX)/include/tilesim/mp.h
	$(INSTHDR) machine/tilesim.h > $(DESTDIR)$(PREFIX)/include/tilesim/tilesim.h
	mkdir -p $(DESTDIR)$(PREFIX)/include/tilesim/mpi
	cp $(addprefix $(IBIN)/,$(MPITOOLS)) $(DESTDIR)$(PREFIX)/bin/
	$(INSTHDR) mpi/mpi.h > $(DESTDIR)$(PREFIX)/include/tilesim/mpi/mpi.h
	$(INSTHDR) mpi/mpi_funcs.h > $(DESTDIR)$(PREFIX)/include/tilesim/mpi/mpi_funcs.h
	mkdir -p $(DESTDIR)$(PREFIX)/lib/tilesim
	cp $(STUBLIB) $(DESTDIR)$(PREFIX)/lib/tilesim/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' machine/tilesim.pc.in \
	  > $(DESTDIR)$(PREFIX)/lib/pkgconfig/tilesim.pc
	cp examples/*.c $(SHARE)/examples/
	mkdir -p $(SHARE)/examples/mpi
	cp examples/mpi/*.c examples/mpi/*.h $(SHARE)/examples/mpi/

# make uninstall PREFIX=... (and DESTDIR, MANDIR, DOCDIR as given to make
# install): every file make install wrote, by the same lists; then the
# folders that are tilesim's own, if nothing else is left in them (a file
# of someone else's stays, and so does its folder).  PREFIX/bin, lib and the
# man folders stay.
UNINST = $(addprefix $(DESTDIR)$(PREFIX)/bin/,$(foreach p,$(PROGS),$(call iname,$(p))) $(if $(PLOT),tilesim-plot) $(MPITOOLS)) \
         $(foreach f,$(wildcard doc/*.[1-9]),$(DESTDIR)$(MANDIR)/man$(subst .,,$(suffix $(f)))/$(notdir $(f))) \
         $(addprefix $(DESTDIR)$(DOCDIR)/,$(notdir $(wildcard doc/*.md))) \
         $(addprefix $(SHARE)/slicerrt/,$(notdir $(wildcard tests/data/slicerrt/*.contours)) README.md) \
         $(addprefix $(SHARE)/rtstruct/,$(notdir $(wildcard tests/data/rtstruct/*.dcm)) README.md) \
         $(addprefix $(SHARE)/examples/,$(notdir $(wildcard examples/*.c))) \
         $(addprefix $(SHARE)/examples/mpi/,$(notdir $(wildcard examples/mpi/*.c examples/mpi/*.h))) \
         $(DESTDIR)$(PREFIX)/lib/libtilesim.a $(DESTDIR)$(PREFIX)/lib/pkgconfig/tilesim.pc \
         $(addprefix $(DESTDIR)$(PREFIX)/include/tilesim/,mp.h tilesim.h mpi/mpi.h mpi/mpi_funcs.h) \
         $(DESTDIR)$(PREFIX)/lib/tilesim/$(notdir $(STUBLIB))
UNINSTDIRS = $(DESTDIR)$(PREFIX)/lib/tilesim $(SHARE)/slicerrt $(SHARE)/rtstruct $(SHARE)/examples/mpi $(SHARE)/examples $(SHARE) $(DESTDIR)$(DOCDIR) \
             $(DESTDIR)$(PREFIX)/include/tilesim/mpi $(DESTDIR)$(PREFIX)/include/tilesim
uninstall:
	rm -f $(UNINST)
	@for d in $(UNINSTDIRS); do if [ -d "$$d" ]; then rmdir "$$d" 2>/dev/null || echo "make uninstall: $$d is not empty: left as it is"; fi; done

clean:
	rm -rf build $(PROGS) $(MPITOOLS) $(addsuffix -mpi,$(MPIPROGS))

FORCE:
.PHONY: all check valgrind tsan bench bench-tile bench-testbed bench-mpi bench-mpirun bench-load bench-cores install install-files uninstall clean mpi mpi-bins smpi-bins simgrid fuzz fuzz-bins FORCE \
        mpi-probe
.SECONDARY:

-include $(shell find build -name '*.d' 2>/dev/null)
