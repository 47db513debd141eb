# kms.mk - `make test-kms`: the KMS back-end on vkms in a QEMU VM (tests/kms/run-kms-test.sh).
# Included by the Makefile. Needs tools/install-deps.sh --kms; the first run builds the kernel
# kit into build/kms/<abi>/ (about 30 s), later runs reuse it.

# seconds allowed for the whole VM run
KMS_TIMEOUT ?= 1500

KMS_PROBE := $(BUILD)/tests/kms_probe

$(KMS_PROBE): tests/kms/kms_probe.c $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(LIB) $(LDLIBS_ALL)

test-kms: $(KMS_PROBE) $(SWELL)
	KMS_TIMEOUT=$(KMS_TIMEOUT) tests/kms/run-kms-test.sh $(BUILD)
