// Validates Kubernetes objects offline against the API schema of Kubernetes 1.33, as the npm
// package kubernetes-models 4.5.1 carries it (generated from that release's OpenAPI spec):
//
//   node validate.js OBJECTS.json...     (each file a JSON array of objects; exit 1 on an error)
//
// Two checks per object, both from that one package:
// - values: the model's validate() (ajv, compiled from the OpenAPI schema): types, formats,
//   enums, required fields (`replicas: "one"`, `cpu: lots`, a probe without a handler's port);
// - fields: every key must be a field of its type, as the package's TypeScript declarations
//   (generated from the same schema) name them, read with the TypeScript compiler's type
//   checker. The OpenAPI schema allows unknown fields, and so does validate(); the API server
//   drops them with at most a warning, so a misspelt `replicas` would be lost silently.
'use strict';

const fs = require('fs');
const path = require('path');
const ts = require('typescript');

const modelsDir = path.dirname(require.resolve('kubernetes-models'));

// "apps/v1" + "StatefulSet" -> "apps/v1/StatefulSet"; the core group "v1" -> "v1/Service".
function modelPath(object) {
  return `${object.apiVersion}/${object.kind}`;
}

function describe(object) {
  const name = (object.metadata || {}).name || '(no name)';
  return `${object.kind || '(no kind)'}/${name}`;
}

// The TypeScript type I<Kind> of every model used, from one virtual source file importing
// them all (one compiler run).
function modelTypes(paths) {
  const entry = path.join(modelsDir, '__validate_entry__.ts');
  const source = paths
    .map((p, i) => `import { I${path.basename(p)} as T${i} } from ${JSON.stringify(
      path.join(modelsDir, p))};\nexport declare const v${i}: T${i};`)
    .join('\n');
  const options = {
    noEmit: true,
    skipLibCheck: true,
    types: [],
    strictNullChecks: false,  // optional fields' types without `| undefined`
    moduleResolution: ts.ModuleResolutionKind.Node10,
    target: ts.ScriptTarget.ES2020,
  };
  const host = ts.createCompilerHost(options);
  const getSourceFile = host.getSourceFile;
  host.getSourceFile = (file, version, ...rest) => file === entry
    ? ts.createSourceFile(file, source, version)
    : getSourceFile.call(host, file, version, ...rest);
  const fileExists = host.fileExists;
  host.fileExists = (file) => file === entry || fileExists.call(host, file);
  const program = ts.createProgram([entry], options, host);
  const checker = program.getTypeChecker();
  const diagnostics = ts.getPreEmitDiagnostics(program, program.getSourceFile(entry));
  if (diagnostics.length > 0) {
    throw new Error(`cannot read the models' types: ${
      ts.flattenDiagnosticMessageText(diagnostics[0].messageText, '\n')}`);
  }
  const types = new Map();
  const symbols = checker.getExportsOfModule(checker.getSymbolAtLocation(
    program.getSourceFile(entry)));
  for (const symbol of symbols) {
    const i = Number(symbol.name.slice(1));
    types.set(paths[i], checker.getTypeOfSymbol(symbol));
  }
  return { checker, types };
}

function editDistance(a, b) {
  const d = Array.from({ length: a.length + 1 }, (_, i) => [i]);
  for (let j = 1; j <= b.length; j++) d[0][j] = j;
  for (let i = 1; i <= a.length; i++) {
    for (let j = 1; j <= b.length; j++) {
      d[i][j] = Math.min(d[i - 1][j] + 1, d[i][j - 1] + 1,
                         d[i - 1][j - 1] + (a[i - 1] === b[j - 1] ? 0 : 1));
    }
  }
  return d[a.length][b.length];
}

// Appends to `errors` every key of `value` that is not a field of `type`, recursively.
function checkFields(checker, value, type, where, errors) {
  if (value === null || typeof value !== 'object') return;  // scalars: validate()'s part
  if (type.flags & (ts.TypeFlags.Any | ts.TypeFlags.Unknown)) return;
  if (type.isUnion()) {
    const shapes = type.types.filter((t) => t.flags & ts.TypeFlags.Object);
    let first = null;
    for (const shape of shapes) {
      const found = [];
      checkFields(checker, value, shape, where, found);
      if (found.length === 0) return;
      if (first === null) first = found;
    }
    if (first !== null) errors.push(...first);
    return;
  }
  if (Array.isArray(value)) {
    if (checker.isArrayType(type)) {
      const element = checker.getTypeArguments(type)[0];
      value.forEach((item, i) => checkFields(checker, item, element, `${where}[${i}]`, errors));
    }
    return;  // not a list where one belongs: validate()'s part
  }
  const properties = checker.getPropertiesOfType(type);
  const indexType = checker.getIndexTypeOfType(type, ts.IndexKind.String);
  if (properties.length === 0 && !indexType) return;  // free-form ({}: RawExtension, FieldsV1)
  for (const [key, item] of Object.entries(value)) {
    const field = where === '' ? key : `${where}.${key}`;
    const property = checker.getPropertyOfType(type, key);
    if (property) {
      checkFields(checker, item, checker.getTypeOfSymbol(property), field, errors);
    } else if (indexType) {
      checkFields(checker, item, indexType, field, errors);
    } else {
      const names = properties.map((p) => p.name);
      const close = names.filter((n) => editDistance(n.toLowerCase(), key.toLowerCase()) <= 2);
      errors.push(`${field}: unknown field (${close.length ? `did you mean ${close.join(' or ')}?`
        : `known here: ${names.join(', ')}`})`);
    }
  }
}

function main(files) {
  if (files.length === 0) {
    console.error('usage: node validate.js OBJECTS.json...');
    return 2;
  }
  const objects = [];
  for (const file of files) {
    const parsed = JSON.parse(fs.readFileSync(file, 'utf8'));
    for (const object of parsed) objects.push({ file, object });
  }
  let failures = 0;
  const report = (file, object, message) => {
    console.error(`${file}: ${describe(object)}: ${message}`);
    failures++;
  };

  const usable = [];
  for (const { file, object } of objects) {
    if (typeof object.apiVersion !== 'string' || typeof object.kind !== 'string') {
      report(file, object, 'no apiVersion or kind');
      continue;
    }
    let Model;
    try {
      Model = require(`kubernetes-models/${modelPath(object)}`)[object.kind];
    } catch (e) {
      Model = undefined;
    }
    if (typeof Model !== 'function') {
      report(file, object, `no such kind in Kubernetes 1.33: apiVersion ${object.apiVersion}, ` +
        `kind ${object.kind}`);
      continue;
    }
    try {
      new Model(object).validate();
    } catch (e) {
      for (const line of String(e.message).split(/, (?=data\/)/)) {
        // ajv's "data/spec/containers/0/image" as "spec.containers[0].image"
        report(file, object, line.replace(/^data\//, '').replace(/\/(\d+)/g, '[$1]')
          .replace(/\//g, '.'));
      }
    }
    usable.push({ file, object });
  }

  const paths = [...new Set(usable.map(({ object }) => modelPath(object)))];
  const { checker, types } = modelTypes(paths);
  for (const { file, object } of usable) {
    const errors = [];
    checkFields(checker, object, types.get(modelPath(object)), '', errors);
    for (const error of errors) report(file, object, error);
  }
  if (failures === 0) {
    console.log(`validate.js: ${objects.length} objects valid (Kubernetes 1.33 API, ` +
      `kubernetes-models 4.5.1): ${files.join(', ')}`);
  }
  return failures === 0 ? 0 : 1;
}

process.exitCode = main(process.argv.slice(2));
