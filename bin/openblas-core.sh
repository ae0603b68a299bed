# Sourced by bin/ff and tests/mpi/run: chooses OpenBLAS's kernels where OpenBLAS does not know the CPU.
# Debian 12's OpenBLAS (0.3.21: every x86-64 kernel family built in, one chosen at start) does not recognise
# processors newer than itself (e.g. Xeons with AVX-512 FP16) and runs its oldest SSE3 kernels (Prescott) there:
# the falling disk's -preset converged took 195.9 CPU s with them, 173.7 s with SkylakeX's (docs/install.md).
# Unless the user set OPENBLAS_CORETYPE, it is set from the CPU's flags to the newest family they allow that every
# OpenBLAS since 0.3.10 has: SkylakeX (AVX-512 F, CD, BW, DQ, VL), else Haswell (AVX2 and FMA); other CPUs keep
# OpenBLAS's own choice. Where OpenBLAS knows the CPU, its double-precision kernels are these families' already.
if [ -z "${OPENBLAS_CORETYPE:-}" ] && [ -r /proc/cpuinfo ]; then
  dlmfsi_flags=" $(grep -m1 '^flags' /proc/cpuinfo | cut -d: -f2) "
  dlmfsi_has() { for f in "$@"; do case "$dlmfsi_flags" in *" $f "*) ;; *) return 1 ;; esac; done; }
  if dlmfsi_has avx512f avx512cd avx512bw avx512dq avx512vl; then export OPENBLAS_CORETYPE=SkylakeX
  elif dlmfsi_has avx2 fma; then export OPENBLAS_CORETYPE=Haswell
  fi
  unset -f dlmfsi_has; unset dlmfsi_flags
fi
