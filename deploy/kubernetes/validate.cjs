// validate.cjs — checks the manifests of deploy/kubernetes offline: every
// document against the Kubernetes JSON schemas (the npm package
// kubernetes-models, whose validators are generated from the Kubernetes OpenAPI
// schemas), then what fluidcastd needs of them (the GPU limit, probes on the
// metrics port's /healthz and /readyz, the token and the TLS certificate and key Secrets mounted as files and
// passed with --token-file, --tls-cert and --tls-key, a volume for the compiled shaders, a grace period longer than the daemon's drain, the
// headless Service's port named "fluidcast" for the SRV records of srv:
// addresses, selectors that match the pods).
//
//   node deploy/kubernetes/validate.cjs NODE_MODULES_DIR DRAIN_MS FILE.yaml...
//
// NODE_MODULES_DIR holds kubernetes-models and yaml (deploy/setup.sh installs
// them into build/npm/node_modules from deploy/kubernetes/package.json).
// Prints one line per document and per failed check; exits 1 on any failure.
'use strict';
const fs = require('fs');
const path = require('path');
const { createRequire } = require('module');

const [modulesDir, drainMsText, ...files] = process.argv.slice(2);
if (!modulesDir || !drainMsText || files.length === 0) {
  console.error('usage: node validate.cjs NODE_MODULES_DIR DRAIN_MS FILE.yaml...');
  process.exit(2);
}
const load = createRequire(path.join(path.resolve(modulesDir), 'validate.cjs'));
const YAML = load('yaml');

let failures = 0;
function fail(where, message) {
  console.log(`FAIL ${where}: ${message}`);
  failures++;
}

// "apps/v1" + "StatefulSet" -> kubernetes-models/apps/v1/StatefulSet; "v1" + "Service" -> kubernetes-models/v1/Service.
function modelFor(apiVersion, kind) {
  try {
    return load(`kubernetes-models/${apiVersion}/${kind}`)[kind];
  } catch (e) {
    return null;
  }
}

function readDocuments(file) {
  const docs = [];
  YAML.parseAllDocuments(fs.readFileSync(file, 'utf8')).forEach((doc, index) => {
    const where = `${path.basename(file)}#${index + 1}`;
    if (doc.errors.length > 0) {
      fail(where, `YAML: ${doc.errors.map((e) => e.message).join('; ')}`);
      return;
    }
    const object = doc.toJS();
    if (object !== null) docs.push({ where, object });
  });
  return docs;
}

function validateSchema({ where, object }) {
  const Model = object && modelFor(String(object.apiVersion), String(object.kind));
  if (!Model) {
    fail(where, `no schema for apiVersion "${object && object.apiVersion}" kind "${object && object.kind}"`);
    return false;
  }
  try {
    new Model(object).validate();
  } catch (e) {
    fail(where, `${object.kind} ${object.metadata && object.metadata.name}: ${e.message}`);
    return false;
  }
  console.log(`ok   ${where}: ${object.kind} ${object.metadata.name} (schema ${object.apiVersion})`);
  return true;
}

// The image's MESA_SHADER_CACHE_DIR (deploy/container/Containerfile; test_kubernetes.sh checks they agree).
const SHADER_CACHE_DIR = '/var/cache/fluidcast';
const byKind = (docs, kind) => docs.filter((d) => d.object.kind === kind);
const matches = (selector, labels) =>
  Object.entries(selector || {}).every(([k, v]) => labels && labels[k] === v) && Object.keys(selector || {}).length > 0;

function checkProbe(where, container, name, wantedPath, metricsPort) {
  const probe = container[name];
  const http = probe && probe.httpGet;
  if (!http) return fail(where, `${name}: no httpGet probe`);
  if (http.path !== wantedPath) fail(where, `${name} asks ${http.path}, expected ${wantedPath}`);
  const port = http.port === 'metrics' ? metricsPort : http.port;
  if (port !== metricsPort) fail(where, `${name} probes port ${http.port}, not the metrics port ${metricsPort}`);
}

function argAfter(args, flag) {
  const i = args.indexOf(flag);
  return i >= 0 ? args[i + 1] : undefined;
}

function checkWorkload({ where, object }, docs, drainMs) {
  const pod = object.spec.template.spec;
  if (!matches(object.spec.selector.matchLabels, object.spec.template.metadata.labels))
    fail(where, 'selector does not match the pod labels');
  const container = pod.containers.find((c) => c.name === 'fluidcastd');
  if (!container) return fail(where, 'no container named fluidcastd');
  const args = container.args || [];
  const ports = Object.fromEntries((container.ports || []).map((p) => [p.name, p.containerPort]));
  if (!ports.fluidcast) fail(where, 'no container port named "fluidcast"');
  if (!ports.metrics) fail(where, 'no container port named "metrics"');
  const listen = argAfter(args, '--listen') || '';
  if (!listen.endsWith(`:${ports.fluidcast}`)) fail(where, `--listen ${listen} is not the "fluidcast" port`);
  const metrics = argAfter(args, '--metrics-listen') || '';
  if (!metrics.endsWith(`:${ports.metrics}`) || metrics.startsWith('127.'))
    fail(where, `--metrics-listen ${metrics}: the kubelet probes the pod address on the "metrics" port`);
  checkProbe(where, container, 'livenessProbe', '/healthz', ports.metrics);
  checkProbe(where, container, 'readinessProbe', '/readyz', ports.metrics);
  const gpus = container.resources && container.resources.limits && container.resources.limits['nvidia.com/gpu'];
  if (!(Number(gpus) >= 1)) fail(where, 'no nvidia.com/gpu limit');
  const grace = pod.terminationGracePeriodSeconds;
  if (!(grace * 1000 > drainMs))
    fail(where, `terminationGracePeriodSeconds ${grace} is not longer than the daemon's drain (${drainMs} ms)`);
  // The GL driver's compiled shaders: a volume at the image's cache folder, so
  // that a container restarted in the pod does not compile every shader again.
  if (!(container.volumeMounts || []).some((m) => m.mountPath === SHADER_CACHE_DIR))
    fail(where, `no volume at ${SHADER_CACHE_DIR}: a restarted container compiles every shader again`);
  // The token, and TLS's certificate and key: each a file of a Secret volume, mounted, given to its option.
  checkSecretFile(where, docs, pod, container, '--token-file', 'anyone reaching the pod could render');
  checkSecretFile(where, docs, pod, container, '--tls-cert', 'the token, particles and images would cross the network in clear');
  checkSecretFile(where, docs, pod, container, '--tls-key', '--tls-cert needs its key');
}

// The file `option` names lies in a mounted Secret volume whose Secret, among the manifests, has that key.
function checkSecretFile(where, docs, pod, container, option, missing) {
  const file = argAfter(container.args || [], option);
  if (!file) return fail(where, `no ${option}: ${missing}`);
  const mount = (container.volumeMounts || []).find((m) => file.startsWith(`${m.mountPath}/`));
  if (!mount) return fail(where, `${option} ${file} lies under no volume mount`);
  const volume = (pod.volumes || []).find((v) => v.name === mount.name);
  const secretName = volume && volume.secret && volume.secret.secretName;
  if (!secretName) return fail(where, `the volume at ${mount.mountPath} is not a Secret`);
  const secret = byKind(docs, 'Secret').find((s) => s.object.metadata.name === secretName);
  const key = path.basename(file);
  const data = secret && { ...(secret.object.data || {}), ...(secret.object.stringData || {}) };
  if (!secret) fail(where, `Secret ${secretName} is not among the manifests`);
  else if (!(key in data)) fail(where, `Secret ${secretName} has no key "${key}" for ${file}`);
}

function checkServices(docs, workload) {
  const labels = workload.object.spec.template.metadata.labels;
  const services = byKind(docs, 'Service');
  for (const { where, object } of services)
    if (!matches(object.spec.selector, labels)) fail(where, `Service ${object.metadata.name} selects no fluidcastd pod`);
  const headless = services.find((s) => s.object.spec.clusterIP === 'None');
  if (!headless) return fail('manifests', 'no headless Service (clusterIP: None) to publish SRV records');
  const port = (headless.object.spec.ports || []).find((p) => p.name === 'fluidcast');
  if (!port || (port.protocol || 'TCP') !== 'TCP')
    fail(headless.where, 'no TCP port named "fluidcast": no _fluidcast._tcp SRV records');
  if (workload.object.kind === 'StatefulSet' && workload.object.spec.serviceName !== headless.object.metadata.name)
    fail(workload.where, `serviceName ${workload.object.spec.serviceName} is not the headless Service`);
}

const drainMs = Number(drainMsText);
const docs = files.flatMap(readDocuments);
const valid = docs.filter(validateSchema);
const workloads = valid.filter((d) => d.object.kind === 'StatefulSet' || d.object.kind === 'Deployment');
if (workloads.length !== 1) fail('manifests', `${workloads.length} StatefulSet/Deployment documents, expected 1`);
else if (failures === 0) {
  checkWorkload(workloads[0], valid, drainMs);
  checkServices(valid, workloads[0]);
}
console.log(failures === 0 ? `kubernetes: ${docs.length} documents valid` : `kubernetes: ${failures} failure(s)`);
process.exit(failures === 0 ? 0 : 1);
