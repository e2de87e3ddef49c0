#!/usr/bin/env bash
# Checks scripts/make-certs with openssl: the CA and the node certificate it makes (names, key
# usages, curve, validity, modes, the chain), that a second run keeps the CA and signs a new
# node certificate with it, and that it refuses a bad name or half a CA. Real processes use its
# output in tests/integration/auth_test.cc.
#
#   tests/deploy/check_make_certs.sh REPO_ROOT
#
# Prints each check; exits 1 at the first that fails.
set -euo pipefail

root=${1:?usage: check_make_certs.sh REPO_ROOT}
make_certs=$root/scripts/make-certs

fail() {
  echo "check_make_certs: FAIL: $*" >&2
  exit 1
}
step() {
  echo "check_make_certs: $*"
}
command -v openssl >/dev/null 2>&1 || fail "openssl is not installed (Debian package openssl)"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dir=$tmp/certs  # not there yet: make-certs makes it

# The text of certificate $1, and its end date in seconds since the epoch.
text() { openssl x509 -in "$1" -noout -text; }
not_after() { date -d "$(openssl x509 -in "$1" -noout -enddate | cut -d= -f2)" +%s; }
# Fails unless certificate $1 ($2 names it) is valid for $3 days from now, give or take one.
valid_for() {
  local days=$(( ($(not_after "$1") - $(date +%s)) / 86400 ))
  [ "$days" -ge $(($3 - 1)) ] && [ "$days" -le "$3" ] || fail "$2 is valid for $days days, want $3"
}

step "make-certs $dir: a CA and a node certificate for server.dcs"
out=$("$make_certs" "$dir" 2>&1) || fail "make-certs $dir failed: $out"
for file in ca.pem ca.key node.pem node.key; do
  [ -f "$dir/$file" ] || fail "no $file in $dir"
done
for file in ca.key node.key; do
  [ "$(stat -c %a "$dir/$file")" = 600 ] || fail "$file has mode $(stat -c %a "$dir/$file"), want 600"
done
for file in ca.pem node.pem; do
  [ "$(stat -c %a "$dir/$file")" = 644 ] || fail "$file has mode $(stat -c %a "$dir/$file"), want 644"
done
[ -z "$(find "$dir" -mindepth 1 -name '.*')" ] || fail "make-certs left $(ls -A "$dir") in $dir"

ca=$(text "$dir/ca.pem")
grep -qE 'CA:TRUE' <<<"$ca" || fail "ca.pem is not a CA (basicConstraints CA:TRUE)"
grep -qE 'Certificate Sign' <<<"$ca" || fail "ca.pem may not sign certificates (keyUsage)"
node=$(text "$dir/node.pem")
san=$(grep -A1 'Subject Alternative Name' <<<"$node" | tail -1 | tr -d ' ')
[ "$san" = "DNS:server.dcs" ] || fail "node.pem names '$san', want DNS:server.dcs and nothing else"
grep -q 'TLS Web Server Authentication, TLS Web Client Authentication' <<<"$node" \
  || fail "node.pem's extendedKeyUsage is not serverAuth and clientAuth"
grep -qE 'CA:FALSE' <<<"$node" || fail "node.pem is not marked CA:FALSE"
for file in ca.pem node.pem; do
  grep -q 'NIST CURVE: P-256' <<<"$(text "$dir/$file")" || fail "$file's key is not EC P-256"
done
for file in ca.key node.key; do
  openssl pkey -in "$dir/$file" -noout -text 2>/dev/null | grep -q 'NIST CURVE: P-256' \
    || fail "$file is not an EC P-256 key"
done
[ "$(openssl x509 -in "$dir/node.pem" -noout -pubkey)" = \
  "$(openssl pkey -in "$dir/node.key" -pubout)" ] || fail "node.key is not node.pem's key"
valid_for "$dir/node.pem" node.pem 365
valid_for "$dir/ca.pem" ca.pem 3650
for purpose in sslserver sslclient; do
  out=$(openssl verify -CAfile "$dir/ca.pem" -purpose "$purpose" "$dir/node.pem" 2>&1) \
    || fail "node.pem does not verify against ca.pem for $purpose: $out"
done

step "make-certs $dir --name other.dcs again: the same CA signs a new node certificate"
ca_before=$(sha256sum "$dir/ca.pem" "$dir/ca.key")
out=$("$make_certs" "$dir" --name other.dcs 2>&1) || fail "make-certs again failed: $out"
[ "$(sha256sum "$dir/ca.pem" "$dir/ca.key")" = "$ca_before" ] || fail "a second run changed the CA"
san=$(grep -A1 'Subject Alternative Name' <<<"$(text "$dir/node.pem")" | tail -1 | tr -d ' ')
[ "$san" = "DNS:other.dcs" ] || fail "--name other.dcs: node.pem names '$san'"
openssl verify -CAfile "$dir/ca.pem" "$dir/node.pem" >/dev/null 2>&1 \
  || fail "the new node.pem does not verify against the CA kept"

step "make-certs refuses a name that is not a DNS name, half a CA, and no DIR"
before=$(sha256sum "$dir"/*)
if out=$("$make_certs" "$dir" --name 'x,IP:10.0.0.1' 2>&1) || [[ "$out" != *"not a DNS name"* ]]; then
  fail "make-certs took --name 'x,IP:10.0.0.1': ${out:-no error}"
fi
[ "$(sha256sum "$dir"/*)" = "$before" ] || fail "a refused run changed $dir"
half=$tmp/half
mkdir "$half"
cp "$dir/ca.pem" "$half/"
if out=$("$make_certs" "$half" 2>&1) || [[ "$out" != *"only one of ca.pem and ca.key"* ]]; then
  fail "make-certs made another CA beside a lone ca.pem: ${out:-no error}"
fi
cmp -s "$dir/ca.pem" "$half/ca.pem" || fail "make-certs overwrote a lone ca.pem"
status=0
"$make_certs" >/dev/null 2>&1 || status=$?
[ "$status" -eq 2 ] || fail "make-certs without DIR exits $status, want 2 (usage)"

step "all checks passed"
