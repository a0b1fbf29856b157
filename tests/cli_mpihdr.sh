#!/bin/sh
# cli_mpihdr.sh -- tilesim's mpi/mpi.h against Open MPI's mpi.h (Open MPI
# 4.1 is an MPI 3.1 library): every function Open MPI declares, tilesim
# declares with the same return and parameter types (gcc -aux-info lists
# both headers' prototypes; MPI_Fint, which is int, aside), and the
# functions only tilesim declares are the ten MPI 3.0 removed,
# MPI_Aint_add/diff (macros in Open MPI) and MPI-4's MPI_Isendrecv and
# MPI_Isendrecv_replace, each with its PMPI_ name.  Where
# $MPICC cannot build an MPI program (MPI_STATUS) or the compiler is not
# gcc, it says so and counts nothing.
. tests/clilib.sh
skip() { echo "cli_mpihdr: skipped: $*"; echo "cli_mpihdr: 0 passed, 0 failed"; exit 0; }

[ "${MPI_STATUS:-}" = yes ] || skip "${MPI_STATUS:-MPI_STATUS is not set (make check probes the MPI compiler)}; mpi/mpi.h was not compared with Open MPI's"
MPICC=${MPICC:-mpicc}
CC=${CC:-cc}
"$MPICC" --showme:version 2>/dev/null | grep -q "Open MPI" || skip "$MPICC is not Open MPI's"
printf '#include <mpi.h>\n' > "$T/h.c"
"$CC" -aux-info "$T/x.aux" -x c -c /dev/null -o "$T/x.o" 2>/dev/null || skip "$CC has no -aux-info (not gcc)"
"$MPICC" -aux-info "$T/ompi.aux" -c "$T/h.c" -o "$T/o1.o" 2>"$T/err" || bad "$MPICC: $(head -2 "$T/err")"
"$CC" -std=c11 -I. -Impi -aux-info "$T/mine.aux" -c "$T/h.c" -o "$T/o2.o" 2>"$T/err" || bad "$CC -I. -Impi: $(head -2 "$T/err")"

# "NAME|RET|T1,T2,..." per function, blanks and MPI_Fint normalised.
protos() {
  sed -n 's/^.*extern \([A-Za-z_][A-Za-z0-9_]*\( \*\)\{0,1\}\) *\(P\{0,1\}MPI_[A-Za-z0-9_]*\) (\(.*\));$/\3|\1|\4/p' "$1" |
    sed 's/MPI_Fint/int/g; s/ //g' | grep -v '_function|\|_fn|' | sort -u
}
protos "$T/ompi.aux" > "$T/ompi"
protos "$T/mine.aux" > "$T/mine"
n=$(wc -l < "$T/ompi")
[ "$n" -ge 800 ] && ok || bad "only $n prototypes found in Open MPI's mpi.h"
# (The typedefs of function types, MPI_User_function and the like, are no
# functions: protos leaves them out.)
cp "$T/ompi" "$T/ompi.f"
cut -d'|' -f1 "$T/ompi.f" | sort -u > "$T/ompi.names"
cut -d'|' -f1 "$T/mine" | sort -u > "$T/mine.names"
missing=$(comm -23 "$T/ompi.names" "$T/mine.names" | tr '\n' ' ')
[ -z "$missing" ] && ok || bad "declared by Open MPI, not by tilesim: $missing"
differ=$(comm -23 "$T/ompi.f" "$T/mine" | cut -d'|' -f1 | tr '\n' ' ')
[ -z "$differ" ] && ok || bad "other types than Open MPI's: $differ"
extra=$(comm -13 "$T/ompi.names" "$T/mine.names" | sed 's/^P//' | sort -u | tr '\n' ' ')
want="MPI_Address MPI_Aint_add MPI_Aint_diff MPI_Errhandler_create MPI_Errhandler_get MPI_Errhandler_set MPI_Isendrecv MPI_Isendrecv_replace MPI_Type_extent MPI_Type_hindexed MPI_Type_hvector MPI_Type_lb MPI_Type_struct MPI_Type_ub "
[ "$extra" = "$want" ] && ok || bad "tilesim alone declares: $extra"
summary
