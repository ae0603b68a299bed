# Sourced by bin/ff and tests/mpi/run before they start mpirun: Open MPI keeps one session folder per host and
# user (/tmp/ompi.<host>.<uid>, its runs in folders below it) that two mpiruns at once share, and the one that ends
# removes it under the other, which then fails to start ("A call to mkdir was unable to create the desired
# directory", orte_init failed). Unless the user set OMPI_MCA_orte_tmpdir_base, each run gets a fresh base folder
# of its own, removed when the script exits (so mpirun must not replace the script: no exec).
if [ -z "${OMPI_MCA_orte_tmpdir_base:-}" ]; then
  dlmfsi_mpi_session=$(mktemp -d "${TMPDIR:-/tmp}/dlmfsi-mpi.XXXXXX")
  export OMPI_MCA_orte_tmpdir_base=$dlmfsi_mpi_session
  trap 'rm -rf "$dlmfsi_mpi_session"' EXIT
fi
