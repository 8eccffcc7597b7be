# Turns the Siconos side of scripts/siconos-options.sh (what Siconos 4.4's solver_options_create
# returns, id by id, internal solvers nested) into capi/src/params/siconos_table.rs: one
# `Defaults` tree per id, with the slots that differ from a fresh options struct (0, and +inf in
# dparam[1]).
function rust_f64(v) {
  if (v == "inf") return "f64::INFINITY"
  if (v == "-inf") return "f64::NEG_INFINITY"
  if (v ~ /^-?[0-9]+$/) return v ".0"
  return v
}
function indent(d) { return sprintf("%" (8 * d + 4) "s", "") }
function close_to(d) {
  while (depth >= d) {
    print indent(depth) "    ],"
    print indent(depth) "},"
    depth--
  }
}
BEGIN {
  depth = -1
  print "//! Siconos 4.4's `solver_options_create(id)` for every solver id of the friction headers, as"
  print "//! data: the slots that differ from a fresh options struct (0, and +inf in dparam[1]) and the"
  print "//! internal solvers, nested. Generated from the installed libsiconos_numerics by"
  print "//! `scripts/siconos-options.sh --write-table`; do not edit by hand."
  print ""
  print "use std::os::raw::{c_double, c_int};"
  print ""
  print "/// One options struct of Siconos' defaults: the slots that differ from a fresh struct (0, and"
  print "/// +inf in dparam[1]) and its internal solvers."
  print "pub(super) struct Defaults {"
  print "    pub id: c_int,"
  print "    pub iparam: &'static [(usize, c_int)],"
  print "    pub dparam: &'static [(usize, c_double)],"
  print "    pub internal: &'static [Defaults],"
  print "}"
  print ""
  print "#[rustfmt::skip]"
  print "pub(super) const TABLE: &[Defaults] = &["
}
/^copy of / { next }
$2 == "solverId" {
  path = $1
  d = gsub(/\.internal\[/, "&", path)
  close_to(d)
  depth = d
  id = $3
  next
}
$2 == "iparam" && depth >= 0 {
  s = ""
  for (k = 3; k <= NF; k++) if ($k != "0") s = s sprintf("(%d, %s), ", k - 3, $k)
  iparam = s
  next
}
$2 == "dparam" && depth >= 0 {
  s = ""
  for (k = 3; k <= NF; k++) {
    base = (k - 3 == 1) ? "inf" : "0"
    if ($k != base) s = s sprintf("(%d, %s), ", k - 3, rust_f64($k))
  }
  sub(/, $/, "", iparam); sub(/, $/, "", s)
  print indent(depth) "Defaults {"
  print indent(depth) "    id: " id ","
  print indent(depth) "    iparam: &[" iparam "],"
  print indent(depth) "    dparam: &[" s "],"
  print indent(depth) "    internal: &["
  next
}
END {
  close_to(0)
  print "];"
}
